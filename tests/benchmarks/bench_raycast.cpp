// The ray-cast visibility pass (renderer::RaycastVisibility) over every pixel of a 1920x1080 center view, and
// through masks of a few shapes (none, one pixel, 5 % as whole 8x8 tiles or scattered 2x2 cells, 25 % of cells,
// every pixel): GPU time from Vulkan timestamps and million rays per second; and the CPU time of building the
// scene's BVH (Embree's builder into s3d's node layout, renderer::SceneBvh), each with both tree qualities (splits,
// fast). Scenes: the built-in ones, and the public glTF scenes (tests/data/scenes/README.md) when the cache holds
// them ($S3D_SCENE_CACHE, else ~/.cache/s3d/scenes). Each timed submission records the pass kRecordsPerTiming
// times, so the GPU stays busy (an idle GPU lowers its clocks). Device: S3D_BENCH_DEVICE (default auto).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "s3d/renderer/raycast_visibility.h"
#include "s3d/renderer/scene_bvh.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/vk/timestamps.h"

#include "bench_context.h"
#include "../support/scene_cache.h"

namespace {

using namespace s3d;
namespace fs = std::filesystem;

constexpr std::uint32_t kWidth = 1920, kHeight = 1080;
constexpr int kRecordsPerTiming = 16;
constexpr std::chrono::milliseconds kWarmUp{1000};  // an idle H200 runs at 345 MHz until about a second of load

using bench::benchContext;

// The scenes to time: every built-in scene, then each public scene found in the cache.
std::vector<std::string> benchScenes() {
  std::vector<std::string> scenes = renderer::builtInSceneNames();
  for (const char* file : {"dungeon/level-dungeon.gltf", "oak/oaktree.gltf", "humanoid/humanoid.gltf",
                           "engine/2CylinderEngine.glb"}) {
    std::error_code error;
    if (fs::is_regular_file(test::sceneCache() / file, error)) scenes.push_back((test::sceneCache() / file).string());
  }
  return scenes;
}

renderer::Scene sceneAtFrame0(const std::string& name) {
  renderer::Scene scene = renderer::loadScene(name);
  scene.camera = renderer::cameraForFrame(scene, 0);
  return scene;
}


void BvhBuild(benchmark::State& state, const std::string& name, renderer::BvhQuality quality) {
  const renderer::Scene scene = sceneAtFrame0(name);
  std::size_t count = 0;
  for (auto _ : state) {
    const renderer::SceneBvh bvh = renderer::SceneBvh::build(scene, quality);
    count = bvh.triangles.size();
    benchmark::DoNotOptimize(count);
  }
  state.counters["triangles"] = double(count);
}

// Which pixels a masked cast casts: none, the centre one, a share of the 8x8 tiles whole (full waves), a share
// of the 2x2 cells scattered (a few rays per wave, as a hybrid's edge cells are), or every pixel through the mask.
enum class MaskShape { Empty, OnePixel, Tiles, Cells, All };

std::vector<std::uint32_t> maskOf(MaskShape shape, double share) {
  std::vector<std::uint32_t> mask(std::size_t(kWidth) * kHeight, shape == MaskShape::All ? 1u : 0u);
  std::mt19937 random(7);
  std::bernoulli_distribution picked(share);
  const std::uint32_t block = shape == MaskShape::Tiles ? 8 : 2;
  if (shape == MaskShape::OnePixel) mask[std::size_t(kHeight / 2) * kWidth + kWidth / 2] = 1;
  if (shape == MaskShape::Tiles || shape == MaskShape::Cells)
    for (std::uint32_t by = 0; by < kHeight; by += block)
      for (std::uint32_t bx = 0; bx < kWidth; bx += block) {
        if (!picked(random)) continue;
        for (std::uint32_t y = by; y < std::min(by + block, kHeight); ++y)
          for (std::uint32_t x = bx; x < std::min(bx + block, kWidth); ++x) mask[std::size_t(y) * kWidth + x] = 1;
      }
  return mask;
}

// `maskShape` null: every pixel without a mask (the pass's unmasked dispatch).
void RaycastPixels(benchmark::State& state, const std::string& name, renderer::BvhQuality quality,
                   std::optional<MaskShape> maskShape, double share) {
  vk::Context& context = benchContext();
  const renderer::Scene scene = sceneAtFrame0(name);
  const renderer::SceneBvh bvh = renderer::SceneBvh::build(scene, quality);
  const renderer::RaycastCamera camera =
      renderer::raycastCamera(scene, renderer::centerViewMatrices(scene, float(kWidth) / float(kHeight)));
  renderer::RaycastVisibility pass(context);
  pass.setBvh(bvh);
  vk::Image ids = vk::createImage(context, VK_FORMAT_R32_UINT, kWidth, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
  vk::Image depth = vk::createImage(context, VK_FORMAT_R32_SFLOAT, kWidth, kHeight, VK_IMAGE_USAGE_STORAGE_BIT);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    vk::transition(cmd, ids, vk::kUndefined, vk::kComputeWrite);
    vk::transition(cmd, depth, vk::kUndefined, vk::kComputeWrite);
  });
  vk::Image maskImage;
  renderer::ShadeMask shadeMask;
  double rayCount = double(kWidth) * kHeight;
  if (maskShape) {
    const std::vector<std::uint32_t> mask = maskOf(*maskShape, share);
    rayCount = double(std::count(mask.begin(), mask.end(), 1u));
    maskImage = vk::createImage(context, VK_FORMAT_R32_UINT, kWidth, kHeight,
                                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    vk::uploadImage(context, maskImage, std::as_bytes(std::span(mask)), vk::kComputeRead);
    shadeMask.image = &maskImage;
  }
  auto recordAll = [&](VkCommandBuffer cmd) {
    for (int i = 0; i < kRecordsPerTiming; ++i) {
      if (i > 0) {  // each recording's writes before the next one's
        vk::transition(cmd, ids, vk::kComputeWrite, vk::kComputeWrite);
        vk::transition(cmd, depth, vk::kComputeWrite, vk::kComputeWrite);
      }
      pass.record(cmd, camera, shadeMask, ids, depth);
    }
  };
  const auto warmUpEnd = std::chrono::steady_clock::now() + kWarmUp;
  do context.submitAndWait(recordAll);
  while (std::chrono::steady_clock::now() < warmUpEnd);
  vk::TimestampQueries timestamps(context, 2);
  double seconds = 0.0;
  for (auto _ : state) {
    context.submitAndWait([&](VkCommandBuffer cmd) {
      timestamps.reset(cmd);
      timestamps.write(cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      recordAll(cmd);
      timestamps.write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    });
    const double iteration = timestamps.elapsedMs(0, 1).value_or(0.0) * 1e-3 / kRecordsPerTiming;
    state.SetIterationTime(iteration);
    seconds += iteration;
  }
  const double rays = rayCount * double(state.iterations());
  state.counters["Mrays/s"] = seconds > 0.0 ? rays / seconds * 1e-6 : 0.0;
  state.counters["triangles"] = double(bvh.triangles.size());
  state.counters["rays"] = rayCount;
  state.SetLabel(context.deviceName());
}

}  // namespace

int main(int argc, char** argv) {
  for (const std::string& name : benchScenes()) {
    const std::string label = renderer::isSceneFile(name) ? fs::path(name).stem().string() : name;
    for (const auto& [quality, tree] : {std::pair{renderer::BvhQuality::SpatialSplits, "splits"},
                                        std::pair{renderer::BvhQuality::Fast, "fast"}}) {
      benchmark::RegisterBenchmark(("BvhBuild/" + std::string(tree) + "/" + label).c_str(), BvhBuild, name, quality)
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("RaycastAllPixels/" + std::string(tree) + "/" + label).c_str(), RaycastPixels,
                                   name, quality, std::nullopt, 1.0)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->MinTime(0.05);
    }
    // A masked cast's cost against its rays: its floor (no pixel, one pixel) and sparse against dense waves.
    for (const auto& [shape, share, shapeName] :
         {std::tuple{MaskShape::Empty, 0.0, "empty"}, std::tuple{MaskShape::OnePixel, 0.0, "one-pixel"},
          std::tuple{MaskShape::Tiles, 0.05, "tiles-5%"}, std::tuple{MaskShape::Cells, 0.05, "cells-5%"},
          std::tuple{MaskShape::Cells, 0.25, "cells-25%"}, std::tuple{MaskShape::All, 1.0, "all"}})
      benchmark::RegisterBenchmark(("RaycastMasked/" + std::string(shapeName) + "/" + label).c_str(), RaycastPixels,
                                   name, renderer::BvhQuality::SpatialSplits, shape, share)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->MinTime(0.05);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
