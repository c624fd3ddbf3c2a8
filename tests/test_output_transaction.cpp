// One tool run's outputs are all-or-nothing: staged privately, moved into place only on commit.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace s3d::io
