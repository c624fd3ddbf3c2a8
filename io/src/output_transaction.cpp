#include "s3d/io/output_transaction.h"

#include <fcntl.h>     // open
#include <stdlib.h>    // mkdtemp
#include <sys/file.h>  // flock
#include <sys/stat.h>  // fstat, stat
#include <unistd.h>    // close

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <map>
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

// Serializes the runs on one output folder while they sweep stale staging folders, create their own, or commit:
// an exclusive flock on the output folder itself, released when this ends. Best effort when the folder cannot
// be opened for reading (no lock, as before); `vanished()` says the folder was removed under us.
class FolderLock {
 public:
  explicit FolderLock(const fs::path& folder) : fd_(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    openErrno_ = fd_ < 0 ? errno : 0;
    while (fd_ >= 0 && ::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
    }
    // Removed (and perhaps made anew by another run) before the lock was ours: the lock guards nothing.
    struct stat locked {}, now {};
    if (fd_ >= 0 && (::fstat(fd_, &locked) != 0 || ::stat(folder.c_str(), &now) != 0 || locked.st_ino != now.st_ino ||
                     locked.st_dev != now.st_dev))
      openErrno_ = ENOENT;
  }
  ~FolderLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  bool vanished() const { return openErrno_ == ENOENT; }

 private:
  int fd_;
  int openErrno_;
};

// A run killed before it could clean up (SIGKILL, power loss) leaves its staging folder behind. A live run
// holds an exclusive flock on its folder's lock file for its whole life and creates the folder and the lock
// under the FolderLock this runs under, so a staging folder whose lock can be taken, or that has none, is stale.
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

// Another run that created the same new output folder removes it again when it fails (while empty): a run
// that finds its folder gone between creating it and staging in it starts over, a bounded number of times.
constexpr int kFolderAttempts = 16;
}  // namespace

OutputTransaction::OutputTransaction(const fs::path& folder) : folder_(fs::absolute(folder).lexically_normal()) {
  if (folder_.filename().empty()) folder_ = folder_.parent_path();
  for (int attempt = 1;; ++attempt) {
    const int error = tryToStage();
    if (error == 0) break;
    if (error == ENOENT && attempt < kFolderAttempts) continue;
    releaseLock();
    rollback();
    failFolder(folder, error == ENOTDIR ? "not a folder" : std::strerror(error));
  }
  previous_ = active.exchange(this);
}

int OutputTransaction::tryToStage() {
  std::error_code error;
  if (!staging_.empty()) {  // an earlier attempt's
    releaseLock();
    fs::remove_all(staging_, error);
    staging_.clear();
  }
  for (fs::path missing = folder_; !missing.empty() && !fs::exists(fs::symlink_status(missing, error));
       missing = missing.parent_path()) {
    if (std::find(createdFolders_.begin(), createdFolders_.end(), missing) == createdFolders_.end())
      createdFolders_.push_back(missing);
    if (missing == missing.parent_path()) break;
  }
  // Innermost first, however the attempts found them.
  std::sort(createdFolders_.begin(), createdFolders_.end(), [](const fs::path& a, const fs::path& b) {
    return std::distance(a.begin(), a.end()) > std::distance(b.begin(), b.end());
  });
  fs::create_directories(folder_, error);
  if (error) return error.value();
  if (!fs::is_directory(folder_, error)) return error ? error.value() : ENOTDIR;
  const FolderLock lock(folder_);
  if (lock.vanished()) return ENOENT;
  removeStaleStaging(folder_);
  std::string pattern = (folder_ / (std::string(kStagingPrefix) + "XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) return errno;
  staging_ = pattern;
  lockFd_ = ::open((staging_ / kStagingLock).c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0600);
  if (lockFd_ < 0 || ::flock(lockFd_, LOCK_EX | LOCK_NB) != 0) return errno;
  return 0;
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
  const FolderLock folderLock(folder_);  // one run's commit at a time: its moves aside and back are its own
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

namespace {
// What `file` is after links (as far as it exists): two paths name one file when these are equal.
fs::path resolved(const fs::path& file) {
  std::error_code error;
  const fs::path path = fs::weakly_canonical(file, error);
  return error ? fs::absolute(file).lexically_normal() : path;
}

// `name` matches `pattern`, whose one '*' (if any) stands for any text.
bool nameMatches(const std::string& pattern, const std::string& name) {
  const std::size_t star = pattern.find('*');
  if (star == std::string::npos) return pattern == name;
  const std::size_t tail = pattern.size() - star - 1;
  return name.size() >= pattern.size() - 1 && name.compare(0, star, pattern, 0, star) == 0 &&
         name.compare(name.size() - tail, tail, pattern, star + 1, tail) == 0;
}

[[noreturn]] void failOverlap(const RunFile& output, const std::string& what, const RunFile& other) {
  throw std::invalid_argument("output " + quoted(output.path) + " would overwrite " + what + " " + quoted(other.path) +
                              " (" + other.option + "); choose another " + output.option);
}

// The outputs by the file they replace: a name in its folder after links (an output replaces a link at its name,
// never writing through it). Each folder is resolved once, so a run of thousands of frames checks quickly.
class OutputIndex {
 public:
  void add(const RunFile& output) {
    const fs::path target = folder(output.path) / output.path.filename();
    if (output.path.filename().string().find('*') != std::string::npos) {
      patterns_.push_back({target, &output});
      return;
    }
    if (const RunFile* other = find(target)) failOverlap(output, "output", *other);
    files_.emplace(target, &output);
  }
  // The output that would replace `file`, or of a link at its name; nullptr when none.
  const RunFile* owner(const fs::path& file) {
    if (const RunFile* output = find(resolved(file))) return output;
    return find(folder(file) / file.filename());
  }

 private:
  fs::path folder(const fs::path& file) {
    const fs::path parent = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    auto [entry, added] = folders_.emplace(parent, fs::path());
    if (added) entry->second = resolved(parent);
    return entry->second;
  }
  const RunFile* find(const fs::path& target) const {
    if (const auto file = files_.find(target); file != files_.end()) return file->second;
    for (const auto& [pattern, output] : patterns_)
      if (pattern.parent_path() == target.parent_path() &&
          nameMatches(pattern.filename().string(), target.filename().string()))
        return output;
    return nullptr;
  }

  std::map<fs::path, fs::path> folders_;
  std::map<fs::path, const RunFile*> files_;
  std::vector<std::pair<fs::path, const RunFile*>> patterns_;
};
}  // namespace

void requireOutputsAreNotInputs(const std::vector<RunFile>& outputs, const std::vector<RunFile>& inputs) {
  OutputIndex index;
  std::error_code error;
  for (const RunFile& output : outputs) {
    if (output.path.empty()) continue;
    if (output.path.filename().string().find('*') == std::string::npos &&
        fs::is_directory(fs::symlink_status(output.path, error)))
      throw std::invalid_argument("output " + quoted(output.path) + " is a folder: it cannot be replaced by a file; " +
                                  "move it or choose another " + output.option);
    index.add(output);
  }
  for (const RunFile& input : inputs)
    if (!input.path.empty())
      if (const RunFile* output = index.owner(input.path)) failOverlap(*output, "input", input);
}

void requireOutputsAreNotInputs(const fs::path& folder, const std::vector<std::string>& outputs,
                                const std::vector<fs::path>& inputs) {
  std::vector<RunFile> outputFiles, inputFiles;
  for (const std::string& name : outputs) outputFiles.push_back({folder / name, "--output"});
  for (const fs::path& input : inputs) inputFiles.push_back({input, "input"});
  requireOutputsAreNotInputs(outputFiles, inputFiles);
}

void OutputTransaction::rollback() noexcept {
  finished_ = true;
  if (active.load() == this) active.store(previous_);
  std::error_code ignored;
  if (!staging_.empty()) fs::remove_all(staging_, ignored);
  for (const fs::path& created : createdFolders_) fs::remove(created, ignored);  // only while empty
}

}  // namespace s3d::io
