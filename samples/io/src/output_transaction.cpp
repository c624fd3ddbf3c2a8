#include "s3d/io/output_transaction.h"

#include <fcntl.h>     // open
#include <stdlib.h>    // mkdtemp
#include <sys/file.h>  // flock
#include <unistd.h>    // close

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

constexpr const char* kStagingPrefix = ".s3d-staging-";
constexpr const char* kStagingLock = ".lock";

// A run killed before it could clean up (SIGKILL, power loss) leaves its staging folder behind. A live run
// holds an exclusive flock on its folder's lock file for its whole life, so a staging folder whose lock can be
// taken (or that has none: killed between creating it and the lock) belongs to no running process.
void removeStaleStaging(const fs::path& folder) {
  std::error_code error;
  for (fs::directory_iterator entry(folder, error), end; !error && entry != end; entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    if (name.rfind(kStagingPrefix, 0) != 0 || !entry->is_directory(error) || entry->is_symlink(error)) continue;
    const int fd = ::open((entry->path() / kStagingLock).c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
    const bool stale = fd < 0 || ::flock(fd, LOCK_EX | LOCK_NB) == 0;
    if (fd >= 0) ::close(fd);
    std::error_code ignored;
    if (stale) fs::remove_all(entry->path(), ignored);
  }
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
  removeStaleStaging(folder_);
  std::string pattern = (folder_ / (std::string(kStagingPrefix) + "XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    const int mkdtempErrno = errno;
    rollback();
    failFolder(folder, std::strerror(mkdtempErrno));
  }
  staging_ = pattern;
  lockFd_ = ::open((staging_ / kStagingLock).c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0600);
  if (lockFd_ < 0 || ::flock(lockFd_, LOCK_EX | LOCK_NB) != 0) {
    const int lockErrno = errno;
    releaseLock();
    rollback();
    failFolder(folder, std::strerror(lockErrno));
  }
  previous_ = active.exchange(this);
}

OutputTransaction::~OutputTransaction() {
  if (!finished_) rollback();
  releaseLock();
}

void OutputTransaction::releaseLock() noexcept {
  if (lockFd_ >= 0) ::close(lockFd_);
  lockFd_ = -1;
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
  auto abandon = [&](const std::string& message) {
    finished_ = true;
    active.store(previous_);
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
    for (const fs::path& created : createdFolders_) fs::remove(created, ignored);  // only while empty
    throw std::runtime_error(message);
  };
  // 1. Nothing moves unless every file can: a folder at an output's name (or at one of its folders' names as a
  //    file) is named and the output folder stays as it was.
  for (const fs::path& relative : staged_) {
    const fs::path target = folder_ / relative;
    std::error_code missing;  // a target or folder that does not exist yet is fine
    if (fs::is_directory(fs::symlink_status(target, missing)))
      abandon("output " + quoted(target) + " is a folder: it cannot be replaced by a file");
    for (fs::path parent = target.parent_path(); parent != folder_ && !parent.empty(); parent = parent.parent_path()) {
      const fs::file_status status = fs::symlink_status(parent, missing);
      if (fs::exists(status) && !fs::is_directory(status))
        abandon("output " + quoted(target) + " needs the folder " + quoted(parent) + ", which is a file");
    }
  }
  // 2. Each file replaced is first moved aside into the staging folder (same file system: renames), so a failure
  //    part-way puts every earlier file back; a link at an output's name is moved, never followed.
  struct Move {
    fs::path target, replaced;  // replaced: empty when nothing was there
  };
  std::vector<Move> moves;
  auto undo = [&] {
    std::error_code ignored;
    for (auto move = moves.rbegin(); move != moves.rend(); ++move) {
      fs::remove(move->target, ignored);
      if (!move->replaced.empty()) fs::rename(move->replaced, move->target, ignored);
    }
  };
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    const fs::path target = folder_ / staged_[i];
    Move move{target, {}};
    fs::create_directories(target.parent_path(), error);
    std::error_code missing;  // symlink_status reports a missing target as an error too
    if (!error && fs::exists(fs::symlink_status(target, missing))) {
      move.replaced = staging_ / (".s3d-replaced-" + std::to_string(i));
      fs::rename(target, move.replaced, error);
      if (error) move.replaced.clear();
    }
    if (!error) fs::rename(staging_ / staged_[i], target, error);
    if (error) {
      const std::string reason = error.message();
      if (!move.replaced.empty()) {
        std::error_code ignored;
        fs::rename(move.replaced, target, ignored);
      }
      undo();
      abandon("cannot move " + quoted(target) + " into place: " + reason);
    }
    moves.push_back(std::move(move));
  }
  finished_ = true;
  active.store(previous_);
  fs::remove_all(staging_, error);  // the staging folder, with the files the run replaced
}

void OutputTransaction::requireReplaceable(const fs::path& folder, const std::vector<std::string>& names) {
  std::error_code error;
  for (const std::string& name : names)
    if (fs::is_directory(fs::symlink_status(folder / name, error)))
      throw std::invalid_argument("output " + quoted(folder / name) +
                                  " is a folder: it cannot be replaced by a file; move it or choose another --output");
}

void requireOutputsAreNotInputs(const fs::path& folder, const std::vector<std::string>& outputs,
                                const std::vector<fs::path>& inputs) {
  OutputTransaction::requireReplaceable(folder, outputs);
  std::error_code error;
  for (const fs::path& input : inputs) {
    if (input.empty()) continue;
    const fs::path resolvedInput = fs::weakly_canonical(input, error);
    for (const std::string& name : outputs) {
      const fs::path output = folder / name;
      const bool same = (!error && fs::weakly_canonical(output, error) == resolvedInput && !error) ||
                        (fs::exists(output) && fs::equivalent(output, input, error) && !error);
      if (same)
        throw std::invalid_argument("output " + quoted(output) + " would overwrite input " + quoted(input) +
                                    "; choose another --output folder");
      error.clear();
    }
  }
}

void OutputTransaction::rollback() noexcept {
  finished_ = true;
  if (active.load() == this) active.store(previous_);
  std::error_code ignored;
  if (!staging_.empty()) fs::remove_all(staging_, ignored);
  for (const fs::path& created : createdFolders_) fs::remove(created, ignored);  // only while empty
}

}  // namespace s3d::io
