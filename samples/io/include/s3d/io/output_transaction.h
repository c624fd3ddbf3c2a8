#pragma once
// All-or-nothing outputs for one tool run. While a transaction is open, every s3d_io write into its folder
// goes to a private staging folder (created exclusively inside the output folder); commit() renames the
// files into place, and a transaction destroyed without commit removes everything it staged and any folder
// it created, so a run that fails late leaves the output folder exactly as it was.
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace s3d::io {

class OutputTransaction {
 public:
  // Creates `folder` if missing (and remembers to remove it again on failure). Throws std::runtime_error
  // naming the folder when it cannot be created or written.
  explicit OutputTransaction(const std::filesystem::path& folder);
  ~OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  // Moves every staged file into the output folder (replacing older files of the same name).
  void commit();

  // Where a write of `file` must go now: inside the open transaction's staging folder when `file` lies in
  // its output folder, else `file` itself. Used by s3d_io's writers.
  static std::filesystem::path stagedTarget(const std::filesystem::path& file);

 private:
  void rollback() noexcept;

  std::filesystem::path folder_;
  std::filesystem::path staging_;
  std::vector<std::filesystem::path> createdFolders_;  // innermost first
  std::vector<std::filesystem::path> staged_;          // relative to folder_
  std::mutex mutex_;
  OutputTransaction* previous_ = nullptr;
  bool finished_ = false;
};

}  // namespace s3d::io
