#include "s3d/frame/layered_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace s3d::frame {
namespace {

// Distance in inverse depth from `u` to a segment's interval (0 inside).
double outside(const stereo::DisparityMapSegment& segment, double u) {
  return u < segment.inverseDepthBegin ? segment.inverseDepthBegin - u
         : u > segment.inverseDepthEnd ? u - segment.inverseDepthEnd
                                       : 0.0;
}

double inverseOf(float depth) {
  if (std::isinf(depth)) return 0.0;
  return depth > 0.0f ? 1.0 / double(depth) : std::numeric_limits<double>::infinity();  // invalid: nearest
}

}  // namespace

renderer::ViewMatrices referenceEyeView(const renderer::Scene& scene, const renderer::ViewMatrices& center,
                                        stereo::Eye eye, const stereo::StereoParameters& parameters,
                                        const stereo::DisparityMapSegment& segment) {
  const double m = parameters.maxSeparation, zpp = parameters.zeroParallaxDistance;
  const bool identity = segment.slope == 1.0 && segment.intercept == 0.0;
  auto terms = [&](float projectionScaleX, double slope, double intercept) {
    if (identity && slope == 1.0 && intercept == 0.0)  // the linear mapping's world layer, in float as always
      return stereo::exactParallaxTerms(projectionScaleX, parameters.maxSeparation, parameters.zeroParallaxDistance);
    const stereo::OffAxisTerms<double> t =
        stereo::affineInverseDepthTerms(double(projectionScaleX), m, zpp, slope, intercept);
    return stereo::OffAxisTerms<float>{float(t.eyeOffset), float(t.frustumShift)};
  };
  const stereo::EyeCamera world = stereo::offAxisEyeCamera(center.worldView, center.worldProjection, eye,
                                                           terms(center.worldProjection[0][0], segment.slope,
                                                                 segment.intercept));
  // The weapon's depth is pushed for the stereo pass, so its reference eyes follow the pushed parallax: the
  // chord of the push, then the segment.
  const glm::vec2 weaponDepths = renderer::firstPersonDepthRange(scene).value_or(glm::vec2(1.0f));
  const glm::dvec2 chord = stereo::pushedInverseDepthChord<double>(
      parameters.weaponDepthOffset, parameters.weaponDepthScale, weaponDepths.x, weaponDepths.y);
  const stereo::EyeCamera firstPerson = stereo::offAxisEyeCamera(
      center.firstPersonView, center.firstPersonProjection, eye,
      identity ? stereo::pushedLayerTerms(center.firstPersonProjection[0][0], parameters.maxSeparation,
                                          parameters.zeroParallaxDistance, parameters.weaponDepthOffset,
                                          parameters.weaponDepthScale, weaponDepths.x, weaponDepths.y)
               : terms(center.firstPersonProjection[0][0], segment.slope * chord.x,
                       segment.intercept + segment.slope * chord.y));
  renderer::ViewMatrices view = center;  // worldFromCamera stays: lighting places first-person objects alike
  view.worldView = world.view;
  view.worldProjection = world.projection;
  view.firstPersonView = firstPerson.view;
  view.firstPersonProjection = firstPerson.projection;
  view.shadowFit = renderer::shadowFitOf(center);  // one set of shadow maps for the frame: the center view's
  return view;
}

std::vector<std::uint8_t> chooseReferenceLayers(const std::vector<DepthImage>& layerDepths,
                                                const std::vector<stereo::DisparityMapSegment>& segments,
                                                std::uint64_t* unresolvedPixels) {
  if (layerDepths.empty() || layerDepths.size() != segments.size() || layerDepths.size() > 255)
    throw std::invalid_argument("chooseReferenceLayers: one depth image per segment (1..255)");
  const std::size_t pixels = layerDepths.front().pixelCount();
  std::vector<std::uint8_t> chosen(pixels, 0);
  std::uint64_t unresolved = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    int best = -1, fallback = 0;
    double bestInverse = -1.0, fallbackDistance = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < layerDepths.size(); ++k) {
      const double u = inverseOf(layerDepths[k].pixels[i]);
      const double distance = outside(segments[k], u);
      if (distance == 0.0 && u > bestInverse) {  // qualifies; the nearest one wins
        best = int(k);
        bestInverse = u;
      }
      if (distance < fallbackDistance) {
        fallback = int(k);
        fallbackDistance = distance;
      }
    }
    if (best < 0) ++unresolved;
    chosen[i] = std::uint8_t(best >= 0 ? best : fallback);
  }
  if (unresolvedPixels) *unresolvedPixels = unresolved;
  return chosen;
}

ReferenceEye renderReferenceEye(renderer::DeferredRenderer& deferred, const renderer::Scene& scene,
                                const renderer::ViewMatrices& center, stereo::Eye eye,
                                const stereo::StereoParameters& parameters, const gpu::DisparityMapConstants& map) {
  const std::vector<stereo::DisparityMapSegment> segments = stereo::disparityMapSegments(map);
  ReferenceEye result;
  result.layers = std::uint32_t(segments.size());
  std::vector<ImageRGBA8> displays;
  std::vector<DepthImage> depths;
  std::vector<ImageRGBA32F> hdrs;
  std::vector<std::vector<std::uint8_t>> transparents, foliages, firstPersons;
  for (const stereo::DisparityMapSegment& segment : segments) {
    const renderer::FrameTimings timings = deferred.render(referenceEyeView(scene, center, eye, parameters, segment));
    if (displays.empty()) result.firstLayerGpuMs = timings.totalGpuMs;
    displays.push_back(deferred.readDisplayColor());
    depths.push_back(deferred.readLinearDepth());
    hdrs.push_back(deferred.readHdrColor());
    transparents.push_back(deferred.readTransparentMask());
    foliages.push_back(deferred.readCutoutMask());
    firstPersons.push_back(deferred.readFirstPersonMask());
  }
  if (segments.size() == 1) {
    result.display = std::move(displays.front());
    result.depth = std::move(depths.front());
    result.hdr = std::move(hdrs.front());
    result.transparent = std::move(transparents.front());
    result.foliage = std::move(foliages.front());
    result.firstPerson = std::move(firstPersons.front());
    result.layerOfPixel.assign(result.depth.pixelCount(), 0);
    return result;
  }
  result.layerOfPixel = chooseReferenceLayers(depths, segments, &result.unresolvedPixels);
  const std::vector<std::uint8_t>& chosen = result.layerOfPixel;
  result.display = displays.front();
  result.depth = depths.front();
  result.hdr = hdrs.front();
  result.transparent = transparents.front();
  result.foliage = foliages.front();
  result.firstPerson = firstPersons.front();
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const std::size_t k = chosen[i];
    std::copy_n(&displays[k].pixels[i * 4], 4, &result.display.pixels[i * 4]);
    result.depth.pixels[i] = depths[k].pixels[i];
    std::copy_n(&hdrs[k].pixels[i * 4], 4, &result.hdr.pixels[i * 4]);
    result.transparent[i] = transparents[k][i];
    result.foliage[i] = foliages[k][i];
    result.firstPerson[i] = firstPersons[k][i];
  }
  return result;
}

}  // namespace s3d::frame
