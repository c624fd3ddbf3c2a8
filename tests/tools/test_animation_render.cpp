// Animated scenes rendered: the skinned arm of skinned_arm.h drawn at a frame's time by the renderer, by
// `s3d render --frame N` (frame N at N / frames-per-second) and by `--sequence`, whose world queries must see the
// pose that is drawn.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "s3d/app/render_job.h"
#include "s3d/app/sequence_job.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene_animation.h"
#include "s3d/renderer/scene_file.h"
#include "skinned_arm.h"
#include "vulkan_test.h"

namespace s3d::renderer {
namespace {
namespace fs = std::filesystem;

constexpr std::uint32_t kSize = 64;

class AnimationRender : public test::VulkanTest {
 protected:
  AnimationRender() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = fs::temp_directory_path() / ("s3d_anim_render_" + std::string(info->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    arm_ = test::SkinnedArm().write(folder_);
  }
  ~AnimationRender() override { fs::remove_all(folder_); }

  ImageRGBA8 render(const Scene& scene) {
    DeferredRenderer renderer(context(), kSize, kSize);
    renderer.setScene(scene);
    renderer.render(centerViewMatrices(scene, 1.0f));
    return renderer.readDisplayColor();
  }

  fs::path folder_, arm_;
};

// Pixels whose largest channel difference exceeds `levels`.
std::size_t pixelsDiffering(const ImageRGBA8& a, const ImageRGBA8& b, int levels) {
  std::size_t count = 0;
  for (std::uint32_t y = 0; y < a.height; ++y)
    for (std::uint32_t x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])) > levels) {
          ++count;
          break;
        }
  return count;
}

TEST_F(AnimationRender, TheArmAtHalfASecondIsDrawnAsTheArmPosedByHand) {
  const Scene rest = loadGltfScene(arm_);
  Scene posed = rest;
  poseScene(posed, 0.5);
  // The same vertices worked out by hand (test_scene_animation.cpp): elbow 45 degrees, shoulder lifted 0.375.
  Scene byHand = rest;
  byHand.animation = nullptr;
  const float c = std::sqrt(0.5f), lift = 0.375f;
  auto elbow = [&](float y) { return glm::vec3(1 + c - y * c, lift + c + y * c, 0); };  // (2, y) turned
  auto middle = [&](float y) { return 0.5f * (glm::vec3(1, y + lift, 0) + glm::vec3(1 - y * c, lift + y * c, 0)); };
  const glm::vec3 hand[6] = {{0, lift - 0.1f, 0}, {0, lift + 0.1f, 0}, middle(-0.1f), middle(0.1f), elbow(-0.1f), elbow(0.1f)};
  for (int v = 0; v < 6; ++v) byHand.meshes[0].vertices[std::size_t(v)].position = hand[v];
  const ImageRGBA8 drawnPosed = render(posed), drawnByHand = render(byHand), drawnRest = render(rest);
  // The vertices agree to float rounding (1e-6 m, a hundred-thousandth of a pixel here): identical images.
  EXPECT_EQ(pixelsDiffering(drawnPosed, drawnByHand, 0), 0u);
  // The forearm left its rest place and the arm rose: well over a hundred of the 4096 pixels change.
  EXPECT_GT(pixelsDiffering(drawnPosed, drawnRest, 16), 100u);
}

TEST_F(AnimationRender, UpdatingTheGeometryDrawsWhatSettingThePosedSceneDraws) {
  Scene scene = loadGltfScene(arm_);
  DeferredRenderer updated(context(), kSize, kSize);
  updated.setScene(scene);
  updated.render(centerViewMatrices(scene, 1.0f));  // a frame at rest first: its shadow and draw state must not linger
  poseScene(scene, 0.5);
  updated.updateGeometry(scene);
  updated.render(centerViewMatrices(scene, 1.0f));
  EXPECT_EQ(pixelsDiffering(updated.readDisplayColor(), render(scene), 0), 0u);  // the same inputs: the same image
}

TEST_F(AnimationRender, UpdatingTheGeometryOfAnotherSceneIsRefused) {
  const Scene arm = loadGltfScene(arm_);
  DeferredRenderer renderer(context(), kSize, kSize);
  renderer.setScene(arm);
  Scene other = arm;
  other.meshes[0].indices.resize(3);
  try {
    renderer.updateGeometry(other);
    ADD_FAILURE() << "updateGeometry took a mesh with other indices";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("scene 'arm': updateGeometry needs the meshes"), std::string::npos) << error.what();
  }
}

TEST_F(AnimationRender, RenderFrameNIsTheSceneAtNOverTheFrameRate) {
  app::RenderJobOptions options;
  options.width = options.height = kSize;
  options.scene = arm_.string();
  options.outputs = {"center.png"};
  options.stereo.edgeCrop = 0.0f;  // the output-size center view, no guard band: comparable with render() below
  options.framesPerSecond = 12.0f;
  options.frame = 6;  // 0.5 s
  options.outputFolder = folder_ / "frame6";
  (void)app::runRenderJob(context(), options);
  options.frame = 0;
  options.outputFolder = folder_ / "frame0";
  (void)app::runRenderJob(context(), options);
  Scene posed = loadGltfScene(arm_);
  poseScene(posed, 0.5);
  const ImageRGBA8 frame6 = io::readPng(folder_ / "frame6" / "center.png");
  const ImageRGBA8 frame0 = io::readPng(folder_ / "frame0" / "center.png");
  EXPECT_EQ(pixelsDiffering(frame6, render(posed), 0), 0u);  // the same scene, size and camera: the same image
  EXPECT_GT(pixelsDiffering(frame6, frame0, 16), 100u);
}

TEST_F(AnimationRender, TheSequencePlaysOneLoopAndItsWorldQueriesSeeThePose) {
  app::SequenceJobOptions options;
  options.width = options.height = kSize;
  options.scene = arm_.string();
  options.framesPerSecond = 1.0f;  // the 2 s loop in two frames: at rest, then the forearm up and the arm lifted
  options.outputFolder = folder_ / "sequence";
  const app::SequenceReport report = app::runSequenceJob(context(), options);
  ASSERT_EQ(report.frames.size(), 2u);
  // The aim ray through the view's centre meets the resting arm at (1, 0, 0); at 1 s the arm's middle is 0.4 m
  // higher, and a query on the rest pose would still report the hit.
  EXPECT_TRUE(report.frames[0].aimSurface.has_value());
  EXPECT_FALSE(report.frames[1].aimSurface.has_value());
  const ImageRGBA8 first = io::readPng(options.outputFolder / "anaglyph_0000.png");
  const ImageRGBA8 second = io::readPng(options.outputFolder / "anaglyph_0001.png");
  EXPECT_GT(pixelsDiffering(first, second, 16), 100u);
}

}  // namespace
}  // namespace s3d::renderer
