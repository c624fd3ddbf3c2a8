#include "s3d/io/output_transaction.h"

#include <stdlib.h>  // mkdtemp

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace s3d::io {
namespace fs = std::filesystem;

namespace {
// The open transaction; writes from any thread of the run are staged by it.
std::atomic<OutputTransaction*> active{nullptr};

// Built by appending: `"'" + std::string` trips GCC 12's -Wrestrict false positive at -O3.
std::string quoted(const fs::path& path) {
  std::string text(1, '\'');
  text += path.string();
  text += '\'';
  return text;
}

[[noreturn]] void failFolder(const fs::path& folder, const std::string& reason) {
  throw std::runtime_error("cannot write output folder " + quoted(folder) + ": " + reason);
}
}  // namespace

OutputTransaction::OutputTransaction(const fs::path& folder) : folder_(fs::absolute(folder).lexically_normal()) {
  if (folder_.filename().empty()) folder_ = folder_.parent_path();
  std::error_code error;
  for (fs::path missing = folder_; !missing.empty() && !fs::exists(fs::symlink_status(missing, error));
       missing = missing.parent_path()) {
    createdFolders_.push_back(missing);
    if (missing == missing.parent_path()) break;
  }
  fs::create_directories(folder_, error);
  if (error) {
    rollback();
    failFolder(folder, error.message());
  }
  if (!fs::is_directory(folder_)) {
    rollback();
    failFolder(folder, "not a folder");
  }
  std::string pattern = (folder_ / ".s3d-staging-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    const int mkdtempErrno = errno;
    rollback();
    failFolder(folder, std::strerror(mkdtempErrno));
  }
  staging_ = pattern;
  previous_ = active.exchange(this);
}

OutputTransaction::~OutputTransaction() {
  if (!finished_) rollback();
}

fs::path OutputTransaction::stagedTarget(const fs::path& file) {
  OutputTransaction* transaction = active.load();
  if (transaction == nullptr || transaction->finished_) return file;
  const fs::path relative = fs::absolute(file).lexically_normal().lexically_relative(transaction->folder_);
  if (relative.empty() || relative == "." || *relative.begin() == "..") return file;
  std::lock_guard lock(transaction->mutex_);
  if (std::find(transaction->staged_.begin(), transaction->staged_.end(), relative) == transaction->staged_.end())
    transaction->staged_.push_back(relative);
  return transaction->staging_ / relative;
}

void OutputTransaction::commit() {
  std::lock_guard lock(mutex_);
  std::error_code error;
  for (const fs::path& relative : staged_) {
    const fs::path target = folder_ / relative;
    fs::create_directories(target.parent_path(), error);
    if (!error) fs::rename(staging_ / relative, target, error);
    if (error) {
      finished_ = true;
      active.store(previous_);
      fs::remove_all(staging_, error);
      throw std::runtime_error("cannot move " + quoted(target) + " into place: " + error.message());
    }
  }
  finished_ = true;
  active.store(previous_);
  fs::remove_all(staging_, error);
}

void OutputTransaction::rollback() noexcept {
  finished_ = true;
  if (active.load() == this) active.store(previous_);
  std::error_code ignored;
  if (!staging_.empty()) fs::remove_all(staging_, ignored);
  for (const fs::path& created : createdFolders_) fs::remove(created, ignored);  // only while empty
}

}  // namespace s3d::io
