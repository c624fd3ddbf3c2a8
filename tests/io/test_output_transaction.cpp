// One tool run's outputs are all-or-nothing: staged privately, moved into place only on commit.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "io_test_support.h"
#include "s3d/io/image_io.h"
#include "s3d/io/output_transaction.h"

namespace s3d::io {
namespace {
namespace fs = std::filesystem;

class OutputTransactionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("s3d_transaction_" + std::string(::testing::UnitTest::GetInstance()
                                                                               ->current_test_info()
                                                                               ->name()) +
                                         "_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "out");
    test::writeFileBytes(root_ / "out" / "old.txt", "old");
    test::writeFileBytes(root_ / "out" / "report.json", "previous report");
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }
  std::vector<std::string> entries(const fs::path& folder) const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path root_;
};

TEST_F(OutputTransactionTest, ARunFailingLateLeavesTheFolderExactlyAsBefore) {
  {
    OutputTransaction outputs(root_ / "out");
    writeTextFile(root_ / "out" / "report.json", "new report");
    writeTextFile(root_ / "out" / "left.png", "new image");
    // no commit: the run failed
  }
  EXPECT_EQ(entries(root_ / "out"), (std::vector<std::string>{"old.txt", "report.json"}));
  EXPECT_EQ(test::readFileBytes(root_ / "out" / "report.json"), "previous report");
  EXPECT_EQ(test::readFileBytes(root_ / "out" / "old.txt"), "old");
}

TEST_F(OutputTransactionTest, NothingAppearsBeforeCommit) {
  OutputTransaction outputs(root_ / "out");
  writeTextFile(root_ / "out" / "left.png", "new image");
  EXPECT_FALSE(fs::exists(root_ / "out" / "left.png"));
}

TEST_F(OutputTransactionTest, CommitMovesEveryFileIntoPlaceAndLeavesNoStaging) {
  {
    OutputTransaction outputs(root_ / "out");
    writeTextFile(root_ / "out" / "report.json", "new report");
    writeTextFile(root_ / "out" / "frames" / "a.txt", "frame a");
    outputs.commit();
  }
  EXPECT_EQ(entries(root_ / "out"), (std::vector<std::string>{"frames", "old.txt", "report.json"}));
  EXPECT_EQ(test::readFileBytes(root_ / "out" / "report.json"), "new report");
  EXPECT_EQ(test::readFileBytes(root_ / "out" / "frames" / "a.txt"), "frame a");
}

TEST_F(OutputTransactionTest, AKilledRunsStagingIsRemovedByTheNextRun) {
  // A run killed outright leaves its staging folder (with or without its lock file); nothing holds the lock.
  const fs::path killed = root_ / "out" / ".s3d-staging-Kill3d";
  const fs::path killedEarly = root_ / "out" / ".s3d-staging-Early1";
  fs::create_directories(killed);
  fs::create_directories(killedEarly);
  test::writeFileBytes(killed / ".lock", "");
  test::writeFileBytes(killed / "left.png", "half-written");
  OutputTransaction next(root_ / "out");
  EXPECT_FALSE(fs::exists(killed));
  EXPECT_FALSE(fs::exists(killedEarly));
}

TEST_F(OutputTransactionTest, ALiveRunsStagingIsNeverTouchedByAnother) {
  OutputTransaction first(root_ / "out");
  writeTextFile(root_ / "out" / "first.txt", "first");  // staged by the open transaction
  std::vector<std::string> before = entries(root_ / "out");
  {
    OutputTransaction second(root_ / "out");  // a second run on the same folder, e.g. another process
  }
  EXPECT_EQ(entries(root_ / "out"), before);
  first.commit();
  EXPECT_EQ(test::readFileBytes(root_ / "out" / "first.txt"), "first");
}

TEST_F(OutputTransactionTest, AFolderCreatedForAFailedRunIsRemovedAgain) {
  {
    OutputTransaction outputs(root_ / "new" / "deeper");
    writeTextFile(root_ / "new" / "deeper" / "left.png", "x");
  }
  EXPECT_EQ(entries(root_), std::vector<std::string>{"out"});
}

TEST_F(OutputTransactionTest, WritesOutsideTheOutputFolderAreNotStaged) {
  OutputTransaction outputs(root_ / "out");
  writeTextFile(root_ / "elsewhere.txt", "direct");
  EXPECT_EQ(test::readFileBytes(root_ / "elsewhere.txt"), "direct");
}

TEST_F(OutputTransactionTest, AnOutputFolderThatIsAFileIsNamed) {
  test::writeFileBytes(root_ / "file", "x");
  const std::string message = test::runtimeErrorMessage([&] { OutputTransaction outputs(root_ / "file"); });
  EXPECT_NE(message.find("file'"), std::string::npos) << message;
  EXPECT_EQ(test::readFileBytes(root_ / "file"), "x");
}

// Processes started together on one new output folder, some committing and some failing (removing the folder
// they created while it is empty): no run fails for another's sake, and no staging folder is left. Bounded:
// 25 rounds of 4 processes (the folder lost under a run failed about one round in 15).
TEST_F(OutputTransactionTest, RunsStartedTogetherOnOneNewFolderNeverFailForEachOther) {
  constexpr int kRounds = 25, kProcesses = 4;
  for (int round = 0; round < kRounds; ++round) {
    const fs::path folder = root_ / ("round" + std::to_string(round)) / "out";
    int start[2];
    ASSERT_EQ(::pipe(start), 0);
    std::vector<pid_t> children;
    for (int process = 0; process < kProcesses; ++process) {
      const pid_t child = ::fork();
      ASSERT_GE(child, 0);
      if (child == 0) {  // waits for the start, then stages one file; odd processes fail before commit
        ::close(start[1]);
        char byte;
        (void)!::read(start[0], &byte, 1);
        int status = 0;
        try {
          OutputTransaction outputs(folder);
          writeTextFile(folder / ("file" + std::to_string(process)), "x");
          if (process % 2 == 0) outputs.commit();
        } catch (...) {
          status = 1;
        }
        ::_exit(status);
      }
      children.push_back(child);
    }
    ::close(start[0]);
    ::close(start[1]);  // every child's read returns now
    for (pid_t child : children) {
      int status = -1;
      ASSERT_EQ(::waitpid(child, &status, 0), child);
      EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "round " << round;
    }
    EXPECT_EQ(entries(folder), (std::vector<std::string>{"file0", "file2"})) << "round " << round;
  }
}

}  // namespace
}  // namespace s3d::io
