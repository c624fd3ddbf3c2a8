// `s3d bench --renderer`: the center frame and each pass per scene, the guard band's wider frame, and the
// masked-render cost on the first scene.
#include <optional>
#include <utility>
#include <vector>

#include "bench_internal.h"
#include "renderer_timing.h"
#include "s3d/app/render_job.h"
#include "s3d/renderer/scene.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/guard_band.h"

namespace s3d::app::bench_detail {

using frame::medianOf;
using frame::timeFrames;

void runRendererTimings(vk::Context& context, const BenchOptions& options, const ValidatedBench& bench,
                        BenchReport& report) {
  renderer::RendererOptions rendererOptions{options.supersample};
  rendererOptions.gbufferShading = options.gbufferShading;
  renderer::DeferredRenderer deferred(context, options.width, options.height, rendererOptions);
  report.gbufferShading = renderer::gbufferShadingName(deferred.gbufferShading());
  // `s3d render`'s guard band (zero-parallax plane held at the nearest depth: the sky's parallax bounds it).
  const stereo::GuardBand band = stereo::guardBandFor(options.stereo.maxSeparation, 1.0, 1.0, options.width,
                                                      kMaxImageSize / options.supersample);
  renderer::DeferredRenderer wide(context, band.renderedWidth(options.width), options.height, rendererOptions);
  std::size_t done = 0;
  for (const std::string& sceneName : bench.scenes) {
    if (options.progress) options.progress({done, bench.scenes.size(), sceneName + " center frame"});
    renderer::Scene scene = renderer::loadScene(sceneName);
    scene.camera = renderer::cameraForFrame(scene, 0);
    deferred.setScene(scene);
    const renderer::ViewMatrices center =
        renderer::centerViewMatrices(scene, float(options.width) / float(options.height),
                                     {options.stereo.weaponDepthOffset, options.stereo.weaponDepthScale});
    (void)deferred.render(center);  // warm-up
    auto [frameMs, passes] = timeFrames(deferred, center, options.repeat);
    wide.setScene(scene);
    const renderer::ViewMatrices wideCenter =
        renderer::centerViewMatrices(scene, float(band.renderedWidth(options.width)) / float(options.height),
                                     {options.stereo.weaponDepthOffset, options.stereo.weaponDepthScale});
    (void)wide.render(wideCenter);  // warm-up
    // Back-to-back pairs: a shared CPU device's load drifts between two separate series.
    std::vector<std::optional<double>> wideRuns, ratios;
    for (int run = 0; run < options.repeat; ++run) {
      const std::optional<double> plainMs = deferred.render(center).totalGpuMs;
      wideRuns.push_back(wide.render(wideCenter).totalGpuMs);
      ratios.push_back(plainMs && wideRuns.back() && *plainMs > 0.0 ? std::optional(*wideRuns.back() / *plainMs)
                                                                     : std::nullopt);
    }
    report.rendererRows.push_back(
        {sceneLabel(sceneName), renderer::trianglesDrawn(scene), frameMs, std::move(passes), band.columns, medianOf(wideRuns), medianOf(ratios),
         context.isCpuDevice() ? std::optional(frame::processCpuMsPerFrame(deferred, center, options.repeat)) : std::nullopt});
    if (done == 0) {  // the masked-render cost scaling, on the first scene
      if (options.progress) options.progress({done, bench.scenes.size(), sceneName + " masked frames"});
      (void)deferred.render(center);  // its depth picks the masks
      report.maskedRenderRows = detail::timeMaskedRenders(context, deferred, center, sceneName, options.repeat);
    }
    ++done;
  }
  if (options.progress) options.progress({done, bench.scenes.size(), "done"});
}

}  // namespace s3d::app::bench_detail
