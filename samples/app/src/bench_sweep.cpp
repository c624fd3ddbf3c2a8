// `s3d bench`'s stereo sweep: per scene the reference eyes of each separation, then every setting timed with the
// frames it is compared with, and its error against the reference eyes.
#include <algorithm>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bench_internal.h"
#include "bench_text.h"
#include "s3d/app/render_job.h"
#include "s3d/frame/layered_reference.h"
#include "s3d/frame/stereo_synthesis.h"
#include "s3d/renderer/scene.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/depth_range_pass.h"
#include "s3d/stereo/disparity_map_pass.h"
#include "s3d/stereo/interleaved_timing.h"
#include "s3d/stereo/synthesis.h"

namespace s3d::app::bench_detail {
namespace {

using namespace bench_text;

struct EyeReferences {
  ImageRGBA8 leftColor, rightColor;
  DepthImage leftDepth, rightDepth;
  std::vector<std::uint8_t> leftTransparent, rightTransparent;  // the error regions the reference eye defines
  std::vector<std::uint8_t> leftFoliage, rightFoliage;
};

// A separation's two reference eyes: colour and depth, and the transparent and cut-out pixels (their error regions).
EyeReferences renderReferenceEyes(renderer::DeferredRenderer& deferred, const renderer::Scene& scene,
                                  const renderer::ViewMatrices& center, const stereo::StereoParameters& parameters) {
  EyeReferences eyes;
  (void)deferred.render(frame::referenceEyeView(scene, center, stereo::Eye::Left, parameters));
  eyes.leftColor = deferred.readDisplayColor();
  eyes.leftDepth = deferred.readLinearDepth();
  eyes.leftTransparent = deferred.readTransparentMask();
  eyes.leftFoliage = deferred.readCutoutMask();
  (void)deferred.render(frame::referenceEyeView(scene, center, stereo::Eye::Right, parameters));
  eyes.rightColor = deferred.readDisplayColor();
  eyes.rightDepth = deferred.readLinearDepth();
  eyes.rightTransparent = deferred.readTransparentMask();
  eyes.rightFoliage = deferred.readCutoutMask();
  return eyes;
}

// The disparity budget's depth reduction and the nonlinear depth-to-parallax mapping of the center frame's
// `linearDepth` (one untimed run each, then `repeat` timed): their median GPU times. The mapping rewrites
// linearDepth in place.
std::pair<std::optional<double>, std::optional<double>> timeDepthPasses(vk::Context& context,
                                                                        const stereo::DepthRangePass& reduction,
                                                                        const stereo::DisparityMapPass& mapping,
                                                                        const gpu::DisparityMapConstants& map,
                                                                        const vk::Image& linearDepth, int repeat) {
  std::vector<double> reductionRuns, mappingRuns;
  for (int run = 0; run <= repeat; ++run)
    if (const std::optional<double> ms = stereo::reduceDepthRangeTimed(context, reduction, linearDepth).gpuMs;
        ms && run > 0)
      reductionRuns.push_back(*ms);
  for (int run = 0; run <= repeat; ++run)
    if (const std::optional<double> ms = stereo::mapDepthTimed(context, mapping, linearDepth, map); ms && run > 0)
      mappingRuns.push_back(*ms);
  return {stereo::medianMs(reductionRuns), stereo::medianMs(mappingRuns)};
}

// A setting's row at one separation: its times, and its eyes compared with the reference eyes over the regions
// (`left`, `right`: the halo and each eye's disocclusion, transparent and foliage pixels). The depth passes'
// times are the caller's.
BenchRow settingRow(const std::string& sceneName, const MethodSetting& setting,
                    const stereo::StereoParameters& parameters, const BenchOptions& options, bool cpuDevice,
                    const frame::SynthesizedEyes& synthesis, const stereo::InterleavedTiming& frames,
                    const EyeReferences& eyes, const stereo::RegionMasks& left, const stereo::RegionMasks& right) {
  const stereo::StereoParameters methodParameters = setting.applyTo(parameters);
  BenchRow row;
  row.scene = sceneLabel(sceneName);
  row.setting = setting;
  row.maxSeparation = parameters.maxSeparation;
  row.cropColumns =
      std::uint32_t(stereo::makeStereoConstants(methodParameters, options.width, options.height).cropBegin);
  row.stereoGpuMs = synthesis.gpuMs;
  row.stereoGpuMsRuns = synthesis.gpuMsRuns;
  row.referenceEyeGpuMs = frames.medians[0];
  row.centerFrameGpuMs = frames.medians[1];
  row.frameWarmUpMs = frames.warmUpMs;
  row.frameWarmUpSettled = frames.settled;
  row.left = stereo::compareEye(synthesis.eyes.left, eyes.leftColor, row.cropColumns, left);
  row.right = stereo::compareEye(synthesis.eyes.right, eyes.rightColor, row.cropColumns, right);
  row.filledLeft = synthesis.filledLeft;
  row.filledRight = synthesis.filledRight;
  row.traffic = stereoPassTraffic(methodParameters, options.width, options.height, cpuDevice);
  if (const std::optional<frame::HybridSynthesis>& hybrid = synthesis.hybrid) {
    const double classified = double(std::max<std::uint64_t>(hybrid->classifiedPixels, 1));
    row.maskedShareLeft = double(hybrid->thresholds[0].maskedPixels) / classified;
    row.maskedShareRight = double(hybrid->thresholds[1].maskedPixels) / classified;
    row.hybridTimings = hybrid->timings;
  }
  return row;
}

}  // namespace

void runSweep(vk::Context& context, const BenchOptions& options, const ValidatedBench& bench, BenchReport& report) {
  renderer::DeferredRenderer deferred(context, options.width, options.height, {options.supersample});
  // Every setting's eyes; the hybrid settings' eye renderer (the center view stays in `deferred`) is made up front,
  // so no renderer is created between a setting's frames and its own timing.
  const bool anyHybrid = std::any_of(bench.settings.begin(), bench.settings.end(),
                                     [](const MethodSetting& s) { return s.method == stereo::StereoMethod::Hybrid; });
  frame::StereoSynthesis synthesis(context, {.width = options.width, .height = options.height,
                                             .renderer = {options.supersample}, .hybrid = anyHybrid,
                                             .hybridSurfaces = options.hybridSurfaces,
                                             .timedRuns = options.repeat});
  const std::size_t total = bench.scenes.size() * bench.separations.size() * bench.settings.size();
  std::size_t done = 0;
  auto progress = [&](const std::string& label) {
    if (options.progress) options.progress({done, total, label});
  };
  for (const std::string& sceneName : bench.scenes) {
    renderer::Scene scene = renderer::loadScene(sceneName);
    scene.camera = renderer::cameraForFrame(scene, 0);
    deferred.setScene(scene);
    synthesis.setScene(scene);
    const renderer::ViewMatrices center =
        renderer::centerViewMatrices(scene, float(options.width) / float(options.height),
                                     {options.stereo.weaponDepthOffset, options.stereo.weaponDepthScale});
    (void)deferred.render(center);  // warm-up: lavapipe compiles pipelines at first use

    // The reference eyes depend on maxSeparation: rendered once per separation, before the center view that the
    // stereo settings run on. Untimed here: their time is measured below, interleaved with the center frame's.
    std::vector<EyeReferences> references;
    for (float separation : bench.separations) {
      progress(sceneName + " references sep " + percentText(separation) + "%");
      stereo::StereoParameters parameters = options.stereo;
      parameters.maxSeparation = separation;
      references.push_back(renderReferenceEyes(deferred, scene, center, parameters));
    }
    (void)deferred.render(center);
    const DepthImage centerDepth = deferred.readLinearDepth();
    const stereo::DepthRangePass reduction(context);
    const stereo::DisparityMapPass mapping(context);
    const gpu::DisparityMapConstants map =
        stereo::nonlinearDisparityMap(stereo::reduceDepthRangeReference(centerDepth), options.stereo.zeroParallaxDistance);
    std::optional<double> depthReductionGpuMs, disparityMapGpuMs;
    // A CPU device has no clocks to bring back, and other load on the machine would keep its frame times from
    // settling: its warm-up is the minimum.
    stereo::WarmUp frameWarmUp;
    if (context.isCpuDevice()) frameWarmUp.maximum = frameWarmUp.minimum;

    for (std::size_t s = 0; s < bench.separations.size(); ++s) {
      stereo::StereoParameters parameters = options.stereo;
      parameters.maxSeparation = bench.separations[s];
      const EyeReferences& eyes = references[s];
      const renderer::ViewMatrices leftEye = frame::referenceEyeView(scene, center, stereo::Eye::Left, parameters);
      parameters.edgeCrop = -1.0f;  // the crop follows the separation, as in `s3d render`
      // Each setting is timed in one warm stretch with the frames it is compared with: the reference eye and the
      // center frame in back-to-back pairs once untimed pairs run at a steady speed, then the setting, before any
      // error is computed. A GPU lowers its clocks through host-side work (metrics, readbacks, a scene upload)
      // and at a low duty cycle, and takes most of a second of frames to raise them: on an H200 an eye timed in
      // the first 500 ms of a scene read twice the center frame timed after it, and a hybrid setting late in a
      // scene's sweep read 1.8x its time.
      std::vector<stereo::InterleavedTiming> frames;
      std::vector<frame::SynthesizedEyes> syntheses;
      for (const MethodSetting& setting : bench.settings) {
        progress(sceneName + " " + setting.name() + " sep " + percentText(parameters.maxSeparation) + "%");
        frames.push_back(stereo::timeInterleaved(
            {[&] { return deferred.render(leftEye).totalGpuMs; }, [&] { return deferred.render(center).totalGpuMs; }},
            options.repeat, frameWarmUp));  // ends on the center frame: the setting's input
        if (s == 0 && frames.size() == 1) {
          // The mapping rewrites linearDepth in place, so the center view is rendered again after it.
          std::tie(depthReductionGpuMs, disparityMapGpuMs) =
              timeDepthPasses(context, reduction, mapping, map, deferred.linearDepth(), options.repeat);
          (void)deferred.render(center);
        }
        syntheses.push_back(synthesis.synthesize({deferred, scene, center, setting.applyTo(parameters)}));
        ++done;
      }
      const std::vector<std::uint8_t> halo = stereo::haloMaskFor(centerDepth, parameters);
      const stereo::RegionMasks left{halo, stereo::disocclusionMaskFor(eyes.leftDepth, centerDepth, parameters, stereo::Eye::Left),
                                     eyes.leftTransparent, eyes.leftFoliage};
      const stereo::RegionMasks right{halo,
                                      stereo::disocclusionMaskFor(eyes.rightDepth, centerDepth, parameters, stereo::Eye::Right),
                                      eyes.rightTransparent, eyes.rightFoliage};
      for (std::size_t i = 0; i < bench.settings.size(); ++i) {
        BenchRow row = settingRow(sceneName, bench.settings[i], parameters, options, context.isCpuDevice(), syntheses[i],
                                  frames[i], eyes, left, right);
        row.depthReductionGpuMs = depthReductionGpuMs;
        row.disparityMapGpuMs = disparityMapGpuMs;
        report.rows.push_back(std::move(row));
      }
    }
  }
  progress("done");
}

}  // namespace s3d::app::bench_detail
