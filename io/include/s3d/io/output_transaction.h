#pragma once
// All-or-nothing outputs for one tool run. While a transaction is open, every s3d_io write into its folder
// goes to a private staging folder (created exclusively inside the output folder); commit() renames the
// files into place, and a transaction destroyed without commit removes everything it staged and any folder
// it created, so a run that fails late leaves the output folder exactly as it was. A run killed outright leaves
// its staging folder; the next transaction on that folder removes it (a live run's is locked, never touched).
// Runs on one folder at once all succeed: each creates its staging folder and commits under an flock on the
// output folder, and one that finds a new folder removed by another's failure creates it again.
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

  // Moves every staged file into the output folder (replacing older files or links of the same name; a link is
  // moved, never followed). Refuses before moving anything when a folder sits at an output's name, and puts every
  // replaced file back when a move fails part-way; throws std::runtime_error naming the file either way.
  void commit();

  // Where a write of `file` must go now: inside the open transaction's staging folder when `file` lies in
  // its output folder, else `file` itself. Used by s3d_io's writers.
  static std::filesystem::path stagedTarget(const std::filesystem::path& file);

 private:
  int tryToStage();  // 0, or the errno that stopped it
  void rollback() noexcept;
  void releaseLock() noexcept;

  std::filesystem::path folder_;
  std::filesystem::path staging_;
  std::vector<std::filesystem::path> createdFolders_;  // innermost first
  std::vector<std::filesystem::path> staged_;          // relative to folder_
  std::mutex mutex_;
  int lockFd_ = -1;  // the staging folder's lock file, flock'ed exclusively while this run lives
  OutputTransaction* previous_ = nullptr;
  bool finished_ = false;
};

// A file a run writes or reads, with the option the user named it by ("--output" for a file in the output
// folder). An output's file name may hold one '*', standing for any text (e.g. "anaglyph_*.png").
struct RunFile {
  std::filesystem::path path;
  std::string option;
};

// Before a run writes anything: throws std::invalid_argument naming both files and their options when one of
// `outputs` resolves, after links, to one of `inputs` (a run would destroy its own input, and each rerun
// again) or to another output, or when an output in an existing folder is itself a folder. The one check every
// command makes with all its files. Empty paths are skipped.
void requireOutputsAreNotInputs(const std::vector<RunFile>& outputs, const std::vector<RunFile>& inputs);

// The same for `outputs` named inside `folder` (option "--output") and unnamed `inputs` (option "input").
void requireOutputsAreNotInputs(const std::filesystem::path& folder, const std::vector<std::string>& outputs,
                                const std::vector<std::filesystem::path>& inputs);

}  // namespace s3d::io
