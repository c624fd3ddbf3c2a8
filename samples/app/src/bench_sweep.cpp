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
    row.maskedShareLeft = double(hybrid->maskedPixels[0]) / classified;
    row.maskedShareRight = double(hybrid->maskedPixels[1]) / classified;
    row.hybridTimings = hybrid->timings;
  }
  return row;
}

// One sweep: the center view's renderer and the syntheses live for the whole sweep, so no renderer is created
// between a setting's frames and its own timing.
class Sweep {
 public:
  Sweep(vk::Context& context, const BenchOptions& options, const ValidatedBench& bench, BenchReport& report)
      : context_(context), options_(options), bench_(bench), report_(report),
        deferred_(context, options.width, options.height, {options.supersample}),
        synthesis_(context, {.width = options.width, .height = options.height, .renderer = {options.supersample},
                             .hybrid = anyHybrid(bench), .hybridSurfaces = options.hybridSurfaces,
                             .concurrentEyes = !options.hybridEyesInTurn, .timedRuns = options.repeat}),
        reduction_(context), mapping_(context),
        total_(bench.scenes.size() * bench.separations.size() * bench.settings.size()) {
    // A CPU device has no clocks to bring back, and other load on the machine would keep its frame times from
    // settling: its warm-up is the minimum.
    if (context.isCpuDevice()) frameWarmUp_.maximum = frameWarmUp_.minimum;
  }

  void run() {
    for (const std::string& sceneName : bench_.scenes) runScene(sceneName);
    progress("done");
  }

 private:
  // What every separation of a scene shares: the center view, its depth and the depth passes' times.
  struct SceneFrame {
    renderer::Scene scene;
    renderer::ViewMatrices center;
    DepthImage centerDepth;
    std::optional<double> depthReductionGpuMs, disparityMapGpuMs;
  };

  static bool anyHybrid(const ValidatedBench& bench) {
    return std::any_of(bench.settings.begin(), bench.settings.end(),
                       [](const MethodSetting& s) { return s.method == stereo::StereoMethod::Hybrid; });
  }

  void progress(const std::string& label) const {
    if (options_.progress) options_.progress({done_, total_, label});
  }

  stereo::StereoParameters parametersAt(float separation) const {
    stereo::StereoParameters parameters = options_.stereo;
    parameters.maxSeparation = separation;
    return parameters;
  }

  void runScene(const std::string& sceneName) {
    SceneFrame shot{renderer::loadScene(sceneName), {}, {}, {}, {}};
    shot.scene.camera = renderer::cameraForFrame(shot.scene, 0);
    deferred_.setScene(shot.scene);
    synthesis_.setScene(shot.scene);
    shot.center = renderer::centerViewMatrices(shot.scene, float(options_.width) / float(options_.height),
                                                {options_.stereo.weaponDepthOffset, options_.stereo.weaponDepthScale});
    (void)deferred_.render(shot.center);  // warm-up: lavapipe compiles pipelines at first use
    // The reference eyes depend on maxSeparation: rendered once per separation, before the center view that the
    // stereo settings run on. Untimed here: their time is measured below, interleaved with the center frame's.
    std::vector<EyeReferences> references;
    for (float separation : bench_.separations) {
      progress(sceneName + " references sep " + percentText(separation) + "%");
      references.push_back(renderReferenceEyes(deferred_, shot.scene, shot.center, parametersAt(separation)));
    }
    (void)deferred_.render(shot.center);
    shot.centerDepth = deferred_.readLinearDepth();
    for (std::size_t s = 0; s < bench_.separations.size(); ++s)
      runSeparation(sceneName, shot, bench_.separations[s], references[s], s == 0);
  }

  // Each setting is timed in one warm stretch with the frames it is compared with: the reference eye and the
  // center frame in back-to-back pairs once untimed pairs run at a steady speed, then the setting, before any
  // error is computed. A GPU lowers its clocks through host-side work (metrics, readbacks, a scene upload) and at a
  // low duty cycle, and takes most of a second of frames to raise them (RESULTS.md, "How the numbers are taken").
  void runSeparation(const std::string& sceneName, SceneFrame& shot, float separation, const EyeReferences& eyes,
                     bool timeDepthPassesFirst) {
    stereo::StereoParameters parameters = parametersAt(separation);
    const renderer::ViewMatrices leftEye = frame::referenceEyeView(shot.scene, shot.center, stereo::Eye::Left, parameters);
    parameters.edgeCrop = -1.0f;  // the crop follows the separation, as in `s3d render`
    std::vector<stereo::InterleavedTiming> frames;
    std::vector<frame::SynthesizedEyes> syntheses;
    for (const MethodSetting& setting : bench_.settings) {
      progress(sceneName + " " + setting.name() + " sep " + percentText(parameters.maxSeparation) + "%");
      frames.push_back(stereo::timeInterleaved(
          {[&] { return deferred_.render(leftEye).totalGpuMs; }, [&] { return deferred_.render(shot.center).totalGpuMs; }},
          options_.repeat, frameWarmUp_));  // ends on the center frame: the setting's input
      if (timeDepthPassesFirst && frames.size() == 1) timeDepthPasses(shot);
      syntheses.push_back(synthesis_.synthesize({deferred_, shot.scene, shot.center, setting.applyTo(parameters)}));
      ++done_;
    }
    const std::vector<std::uint8_t> halo = stereo::haloMaskFor(shot.centerDepth, parameters);
    const stereo::RegionMasks left{halo, stereo::disocclusionMaskFor(eyes.leftDepth, shot.centerDepth, parameters, stereo::Eye::Left),
                                   eyes.leftTransparent, eyes.leftFoliage};
    const stereo::RegionMasks right{halo,
                                    stereo::disocclusionMaskFor(eyes.rightDepth, shot.centerDepth, parameters, stereo::Eye::Right),
                                    eyes.rightTransparent, eyes.rightFoliage};
    for (std::size_t i = 0; i < bench_.settings.size(); ++i) {
      BenchRow row = settingRow(sceneName, bench_.settings[i], parameters, options_, context_.isCpuDevice(), syntheses[i],
                                frames[i], eyes, left, right);
      row.depthReductionGpuMs = shot.depthReductionGpuMs;
      row.disparityMapGpuMs = shot.disparityMapGpuMs;
      report_.rows.push_back(std::move(row));
    }
  }

  // The depth reduction and the nonlinear mapping on the warm center frame; the mapping rewrites linearDepth in
  // place, so the center view is rendered again after it.
  void timeDepthPasses(SceneFrame& shot) {
    const gpu::DisparityMapConstants map = stereo::nonlinearDisparityMap(
        stereo::reduceDepthRangeReference(shot.centerDepth), options_.stereo.zeroParallaxDistance);
    std::tie(shot.depthReductionGpuMs, shot.disparityMapGpuMs) = bench_detail::timeDepthPasses(
        context_, reduction_, mapping_, map, deferred_.linearDepth(), options_.repeat);
    (void)deferred_.render(shot.center);
  }

  vk::Context& context_;
  const BenchOptions& options_;
  const ValidatedBench& bench_;
  BenchReport& report_;
  renderer::DeferredRenderer deferred_;
  frame::StereoSynthesis synthesis_;  // every setting's eyes; the hybrid's eye renderer made up front
  const stereo::DepthRangePass reduction_;  // made before any timing, as everything else
  const stereo::DisparityMapPass mapping_;
  stereo::WarmUp frameWarmUp_;
  std::size_t total_ = 0, done_ = 0;
};

}  // namespace

void runSweep(vk::Context& context, const BenchOptions& options, const ValidatedBench& bench, BenchReport& report) {
  Sweep(context, options, bench, report).run();
}

}  // namespace s3d::app::bench_detail
