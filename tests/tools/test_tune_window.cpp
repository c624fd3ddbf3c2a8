// `s3d tune` in a real window (under Xvfb in CI): scripted input for a few frames, a screenshot of the window,
// and its view area against `s3d render`'s offscreen anaglyph of the same frame and parameters.
// Its own binary, so ctest can run it under xvfb-run and read exit status 77 as "skipped" (no display).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "s3d/app/render_job.h"
#include "s3d/io/image_io.h"
#include "s3d/tune/tune_window.h"

namespace s3d {
namespace {

namespace fs = std::filesystem;

constexpr int kSkipExitCode = 77;  // `s3d tune` could open no window

TEST(TuneWindow, ScreenshotViewMatchesTheOffscreenAnaglyphOfTheSameFrame) {
  const fs::path folder = fs::temp_directory_path() / ("s3d_tune_window_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const fs::path shot = folder / "shot.png";
  {
    // The budget off: the parameters below are compared as given. Walks and turns for two frames in another view, then jumps back onto the camera path (courtyard frame 3)
    // in the anaglyph view with 2x2 supersampling: a frame `s3d render --frame 3 --supersample 2` renders too.
    std::ofstream script(folder / "script.txt");
    script << "set maxSeparation 0.03\nset zeroParallaxDistance 2\nview sbs\nhold w 2\nlook 30 -5\nwait 2\n"
              "view anaglyph\nframe 3\nsupersample 2\nscreenshot "
           << shot.string() << "\nquit\n";
  }
  const std::string command = std::string("'") + S3D_TOOL + "' tune --resolution 64x48 --no-reference --validation --disparity-budget off "
                              "--script '" + (folder / "script.txt").string() + "'";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << command;
  if (WEXITSTATUS(status) == kSkipExitCode) {
    fs::remove_all(folder);
    GTEST_SKIP() << "s3d tune could not open a window (no display)";
  }
  ASSERT_EQ(WEXITSTATUS(status), 0) << command;

  app::RenderJobOptions options;
  options.width = 64;
  options.height = 48;
  options.frame = 3;
  options.supersample = 2;
  options.stereo.maxSeparation = 0.03f;
  options.stereo.zeroParallaxDistance = 2.0f;
  options.stereo.edgeCrop = 0.03f;  // s3d tune crops the edges (it has no guard band)
  options.outputs = {"anaglyph.png"};
  options.outputFolder = folder / "render";
  vk::Context context;
  (void)app::runRenderJob(context, options);

  const ImageRGBA8 screenshot = io::readPng(shot);
  const ImageRGBA8 offscreen = io::readPng(options.outputFolder / "anaglyph.png");
  ASSERT_EQ(screenshot.width, 64u + tune::kPanelWidth);
  ASSERT_EQ(screenshot.height, std::uint32_t(tune::kMinWindowHeight));
  // The view sits 1:1 at the top left and is blitted between 8-bit UNORM formats, which is exact: every pixel
  // must match (tolerance 0).
  std::size_t differing = 0;
  for (std::uint32_t y = 0; y < offscreen.height; ++y)
    for (std::uint32_t x = 0; x < offscreen.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (screenshot.at(x, y)[c] != offscreen.at(x, y)[c]) {
          ++differing;
          break;
        }
  EXPECT_EQ(differing, 0u) << "of " << offscreen.pixelCount() << " view pixels";
  fs::remove_all(folder);
}

TEST(TuneNoDisplay, ExitsWithStatus77AndOneErrorLine) {
  const fs::path folder = fs::temp_directory_path() / ("s3d_tune_nodisplay_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const fs::path log = folder / "stderr.txt";
  const std::string command = std::string("env -u DISPLAY -u WAYLAND_DISPLAY '") + S3D_TOOL +
                              "' tune --resolution 16x16 --frames 1 2> '" + log.string() + "'";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << command;
  EXPECT_EQ(WEXITSTATUS(status), kSkipExitCode);
  std::ifstream file(log);
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.rfind("s3d: error: cannot open a window: ", 0), 0u) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  fs::remove_all(folder);
}

}  // namespace
}  // namespace s3d

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  // ctest's SKIP_RETURN_CODE: a run whose only outcome was a skip reports 77.
  const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
  if (result == 0 && unit.skipped_test_count() > 0 && unit.successful_test_count() == 0)
    return s3d::kSkipExitCode;
  return result;
}
