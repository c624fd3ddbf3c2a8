// GPU time (Vulkan timestamps) of the stereo pass against the center frame and one two-pass reference eye,
// measured in one run so the ratios compare like with like. Device: S3D_BENCH_DEVICE (default auto).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <memory>
#include <vector>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/stereo/hybrid.h"
#include "s3d/stereo/hybrid_pass.h"
#include "s3d/stereo/stereo.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/iterative_pass.h"
#include "s3d/stereo/stereo_pass.h"
#include "s3d/vk/timestamps.h"
#include "bench_context.h"

namespace {

using namespace s3d;

using bench::benchContext;

// One renderer per resolution with the default scene loaded and a warm center frame on its outputs.
struct Setup {
  renderer::Scene scene = renderer::makeCourtyardScene();
  renderer::DeferredRenderer deferred;
  renderer::ViewMatrices center;
  renderer::ViewMatrices leftEye;
  stereo::StereoParameters parameters;
  Setup(std::uint32_t width, std::uint32_t height) : deferred(benchContext(), width, height) {
    deferred.setScene(scene);
    center = renderer::centerViewMatrices(scene, float(width) / float(height));
    leftEye = center;
    stereo::EyeCamera world = stereo::offAxisEyeCamera(center.worldView, center.worldProjection, stereo::Eye::Left,
                                                       parameters.maxSeparation, parameters.zeroParallaxDistance);
    stereo::EyeCamera firstPerson =
        stereo::offAxisEyeCamera(center.firstPersonView, center.firstPersonProjection, stereo::Eye::Left,
                                 parameters.maxSeparation, parameters.zeroParallaxDistance);
    leftEye.worldView = world.view;
    leftEye.worldProjection = world.projection;
    leftEye.firstPersonView = firstPerson.view;
    leftEye.firstPersonProjection = firstPerson.projection;
    deferred.render(leftEye);  // warm-up: lavapipe compiles shaders at first use
    deferred.render(center);
  }
};

Setup& setupFor(std::uint32_t width, std::uint32_t height) {
  static std::map<std::pair<std::uint32_t, std::uint32_t>, std::unique_ptr<Setup>> setups;
  auto& setup = setups[{width, height}];
  if (!setup) setup = std::make_unique<Setup>(width, height);
  return *setup;
}

void reportDevice(benchmark::State& state) { state.SetLabel(benchContext().deviceName()); }

void CenterFrame(benchmark::State& state) {
  Setup& setup = setupFor(std::uint32_t(state.range(0)), std::uint32_t(state.range(1)));
  for (auto _ : state) state.SetIterationTime(setup.deferred.render(setup.center).totalGpuMs.value_or(0.0) * 1e-3);
  reportDevice(state);
}

void ReferenceEye(benchmark::State& state) {
  Setup& setup = setupFor(std::uint32_t(state.range(0)), std::uint32_t(state.range(1)));
  for (auto _ : state) state.SetIterationTime(setup.deferred.render(setup.leftEye).totalGpuMs.value_or(0.0) * 1e-3);
  setup.deferred.render(setup.center);  // leave the center view on the outputs for the stereo benchmark
  reportDevice(state);
}

// Times `pass` on the renderer's own center color and linear depth, both eyes in one dispatch per iteration.
template <typename Pass, typename Constants>
void timeStereoDispatches(benchmark::State& state, Setup& setup, const Pass& pass, const Constants& constants) {
  vk::Context& context = benchContext();
  const std::uint32_t width = setup.deferred.width(), height = setup.deferred.height();
  vk::Image left = vk::createImage(context, stereo::StereoPass::kColorFormat, width, height, VK_IMAGE_USAGE_STORAGE_BIT);
  vk::Image right = vk::createImage(context, stereo::StereoPass::kColorFormat, width, height, VK_IMAGE_USAGE_STORAGE_BIT);
  const vk::Image& color = setup.deferred.displayColor();
  const vk::Image& depth = setup.deferred.linearDepth();
  context.submitAndWait([&](VkCommandBuffer cmd) {
    stereo::StereoPass::recordInputBarriers(cmd, color, depth, left, right);
    pass.record(cmd, color, depth, left, right, constants);  // warm-up
  });
  vk::TimestampQueries timestamps(context, 2);
  for (auto _ : state) {
    context.submitAndWait([&](VkCommandBuffer cmd) {
      timestamps.reset(cmd);
      timestamps.write(cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      pass.record(cmd, color, depth, left, right, constants);
      timestamps.write(cmd, 1, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    });
    state.SetIterationTime(timestamps.elapsedMs(0, 1).value_or(0.0) * 1e-3);
  }
  context.submitAndWait([&](VkCommandBuffer cmd) { stereo::StereoPass::recordInputRelease(cmd, color, depth); });
  const std::uint64_t bytesPerPixel = 4 + 4 + 4 + 4;  // color + depth read once (ideal caching), two eyes written
  state.SetBytesProcessed(std::int64_t(state.iterations() * bytesPerPixel * width * height));
  reportDevice(state);
}

// The fourth argument picks the kernel: 0 per pixel, 1 row tiles (docs/DESIGN.md "Row tiles").
stereo::StereoKernel kernelArgument(const benchmark::State& state) {
  return state.range(3) == 0 ? stereo::StereoKernel::PerPixel : stereo::StereoKernel::RowTiles;
}

// Seed or search (third argument: the search's tap count, 0 for the seed, Listing 4.5).
void StereoPass(benchmark::State& state) {
  Setup& setup = setupFor(std::uint32_t(state.range(0)), std::uint32_t(state.range(1)));
  stereo::StereoParameters parameters = setup.parameters;
  if (state.range(2) > 0) {
    parameters.method = stereo::StereoMethod::Search;
    parameters.searchTaps = int(state.range(2));
  }
  timeStereoDispatches(state, setup, stereo::StereoPass(benchContext(), kernelArgument(state)),
                       stereo::makeStereoConstants(parameters, setup.deferred.width(), setup.deferred.height()));
}

// The iterative method (third argument: iterations).
void IterativePass(benchmark::State& state) {
  Setup& setup = setupFor(std::uint32_t(state.range(0)), std::uint32_t(state.range(1)));
  timeStereoDispatches(state, setup, stereo::IterativeStereoPass(benchContext(), kernelArgument(state)),
                       stereo::makeIterativeConstants(setup.parameters, int(state.range(2)), setup.deferred.width(),
                                                      setup.deferred.height()));
}

// The hybrid method's classification (both eyes, default budget and search base: the classify, threshold and mask
// passes) in a row shape (third argument: 0 the device's own, hybridRowShapeFor; 1 the fallback, many invocations
// sharing each chunk's slots) on cells of the fourth argument's pixels, timed from before its first dispatch to
// after the masks; the counter classifyMs is the classify pass alone (with the cells' depth before it).
void HybridClassify(benchmark::State& state) {
  Setup& setup = setupFor(std::uint32_t(state.range(0)), std::uint32_t(state.range(1)));
  vk::Context& context = benchContext();
  const stereo::HybridRowShape shape =
      state.range(2) == 0 ? stereo::hybridRowShapeFor(context) : stereo::kHybridFallbackRowShape;
  const stereo::HybridPass pass(context, shape);
  stereo::StereoParameters parameters = setup.parameters;
  parameters.method = stereo::StereoMethod::Hybrid;
  parameters.hybridCell = int(state.range(3));
  const std::uint32_t width = setup.deferred.width(), height = setup.deferred.height();
  const gpu::HybridConstants constants = stereo::makeHybridConstants(parameters, width, height);
  stereo::HybridPass::Images images = pass.createImages(width, height, parameters.hybridCell);
  vk::Image left = vk::createImage(context, stereo::StereoPass::kColorFormat, width, height, VK_IMAGE_USAGE_STORAGE_BIT);
  vk::Image right = vk::createImage(context, stereo::StereoPass::kColorFormat, width, height, VK_IMAGE_USAGE_STORAGE_BIT);
  const vk::Image& color = setup.deferred.displayColor();
  const vk::Image& depth = setup.deferred.linearDepth();
  vk::TimestampQueries timestamps(context, 4);
  bool timed = false;
  auto record = [&](VkCommandBuffer cmd) {
    stereo::StereoPass::recordInputBarriers(cmd, color, depth, left, right);
    if (timed) {
      timestamps.reset(cmd);
      timestamps.write(cmd, 0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    }
    int dispatches = 0;
    pass.recordMasks(cmd, depth, images, constants, [&] {
      if (timed) timestamps.write(cmd, std::uint32_t(++dispatches), VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    });
    stereo::StereoPass::recordInputRelease(cmd, color, depth);
  };
  context.submitAndWait(record);  // warm-up
  timed = true;
  double classifyMs = 0.0;
  for (auto _ : state) {
    context.submitAndWait(record);
    state.SetIterationTime(timestamps.elapsedMs(0, 3).value_or(0.0) * 1e-3);
    classifyMs += timestamps.elapsedMs(0, 1).value_or(0.0);
  }
  state.counters["classifyMs"] = classifyMs / double(std::max<benchmark::IterationCount>(state.iterations(), 1));
  state.SetLabel(context.deviceName() + ", row group " + std::to_string(shape.rowGroup) + " x chunk " +
                 std::to_string(shape.chunk) + (shape.independentRuns ? ", independent runs" : ", shared slots") +
                 ", cell " + std::to_string(parameters.hybridCell));
}

void resolutions(benchmark::internal::Benchmark* benchmark) {
  benchmark->Args({1280, 720})->Args({1920, 1080})->UseManualTime()->Unit(benchmark::kMillisecond);
}

void methods(benchmark::internal::Benchmark* benchmark) {
  for (std::int64_t kernel : {0, 1})
    for (std::int64_t taps : {0, 8, 16}) benchmark->Args({1280, 720, taps, kernel})->Args({1920, 1080, taps, kernel});
  benchmark->ArgNames({"width", "height", "searchTaps", "rowTiles"})->UseManualTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(CenterFrame)->Apply(resolutions)->MinTime(0.2);
BENCHMARK(ReferenceEye)->Apply(resolutions)->MinTime(0.2);
BENCHMARK(StereoPass)->Apply(methods)->MinTime(0.2);
BENCHMARK(HybridClassify)
    ->Args({1280, 720, 0, 1})
    ->Args({1280, 720, 0, 2})
    ->Args({1280, 720, 1, 2})
    ->Args({1920, 1080, 0, 1})
    ->Args({1920, 1080, 0, 2})
    ->ArgNames({"width", "height", "fallbackShape", "cell"})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(IterativePass)
    ->Args({1280, 720, 6, 0})
    ->Args({1920, 1080, 6, 0})
    ->Args({1920, 1080, 4, 0})
    ->Args({1920, 1080, 2, 0})
    ->Args({1920, 1080, 6, 1})
    ->Args({1920, 1080, 2, 1})
    ->ArgNames({"width", "height", "iterations", "rowTiles"})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.2);

}  // namespace

BENCHMARK_MAIN();
