#include "s3d/stereo/temporal.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "s3d/stereo/reprojection.h"

namespace s3d::stereo {
namespace {

struct Sum {
  double levels = 0.0;
  std::uint64_t pixels = 0;
  void add(double value) { levels += value, ++pixels; }
  FlickerRegion region() const { return {pixels ? levels / double(pixels) : 0.0, pixels}; }
};

void requireFrame(const EyeFrame& frame, const char* which) {
  if (!frame.synthesized || !frame.reference || !frame.referenceDepth)
    throw std::invalid_argument(std::string("temporal flicker: the ") + which + " frame lacks an image");
  requireSameSize(*frame.synthesized, *frame.reference, "temporal flicker (synthesized vs reference)");
  requireSameSize(*frame.reference, *frame.referenceDepth, "temporal flicker (reference vs its depth)");
  if (!frame.firstPerson.empty() && frame.firstPerson.size() != frame.reference->pixelCount())
    throw std::invalid_argument("temporal flicker: the first-person mask does not match the image size");
}

bool flagged(const std::vector<std::uint8_t>& mask, std::size_t i) { return !mask.empty() && mask[i] != 0; }

// The metric with `reproject(i, pixel, inverseDepth)` giving where pixel i's surface was in the previous frame.
template <typename Reproject>
FlickerStats flicker(const EyeFrame& current, const EyeFrame& previous, const std::vector<std::uint8_t>& halo,
                     const std::vector<std::uint8_t>& disocclusion, Reproject reproject) {
  requireFrame(current, "current");
  requireFrame(previous, "previous");
  requireSameSize(*current.reference, *previous.reference, "temporal flicker (current vs previous frame)");
  const std::uint32_t width = current.reference->width, height = current.reference->height;
  const std::size_t count = current.reference->pixelCount();
  if ((!halo.empty() && halo.size() != count) || (!disocclusion.empty() && disocclusion.size() != count))
    throw std::invalid_argument("temporal flicker: a region mask does not match the image size");

  auto error = [](const EyeFrame& frame, std::size_t i, int c) {
    return int(frame.synthesized->pixels[i * 4 + std::size_t(c)]) - int(frame.reference->pixels[i * 4 + std::size_t(c)]);
  };
  auto insidePrevious = [&](int x, int y) {
    return y >= 0 && y < int(height) && x >= int(previous.cropColumns) && x + int(previous.cropColumns) < int(width);
  };
  Sum all, haloSum, disocclusionSum;
  std::uint64_t newlyVisible = 0;
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = current.cropColumns; x + current.cropColumns < width; ++x) {
      const std::size_t i = std::size_t(y) * width + x;
      const bool firstPerson = flagged(current.firstPerson, i);
      // Where the surface was: the weapon stays on screen; the world moves with its depth and the camera.
      gpu::vec3 was(float(x) + 0.5f, float(y) + 0.5f, 0.0f);
      if (!firstPerson) {
        const float inverseDepth = gpu::inverseDepthOf(*current.referenceDepth->at(x, y));
        was = inverseDepth < 0.0f ? gpu::vec3(0.0f, 0.0f, -1.0f)
                                  : reproject(i, gpu::vec2(float(x) + 0.5f, float(y) + 0.5f), inverseDepth);
        if (was.z < 0.0f) {
          ++newlyVisible;
          continue;
        }
      }
      const gpu::ivec2 topLeft = gpu::bilinearTopLeft({was.x, was.y});
      const gpu::vec4 weights = gpu::bilinearWeights({was.x, was.y});
      double weightSum = 0.0;
      std::array<double, 3> previousError{};
      for (int tap = 0; tap < 4; ++tap) {
        const int tx = topLeft.x + (tap & 1), ty = topLeft.y + (tap >> 1);
        if (!(weights[tap] >= S3D_REPROJECTION_MIN_WEIGHT) || !insidePrevious(tx, ty)) continue;
        const std::size_t j = std::size_t(ty) * width + std::size_t(tx);
        if (flagged(previous.firstPerson, j) != firstPerson) continue;
        if (!firstPerson && !gpu::sameSurface(was.z, gpu::inverseDepthOf(*previous.referenceDepth->at(std::uint32_t(tx), std::uint32_t(ty)))))
          continue;
        weightSum += double(weights[tap]);
        for (int c = 0; c < 3; ++c) previousError[std::size_t(c)] += double(weights[tap]) * error(previous, j, c);
      }
      if (!(weightSum > 0.0)) {
        ++newlyVisible;
        continue;
      }
      double levels = 0.0;
      for (int c = 0; c < 3; ++c) levels += std::abs(double(error(current, i, c)) - previousError[std::size_t(c)] / weightSum);
      const double value = levels / 3.0;
      all.add(value);
      if (flagged(halo, i)) haloSum.add(value);
      if (flagged(disocclusion, i)) disocclusionSum.add(value);
    }
  return {all.region(), haloSum.region(), disocclusionSum.region(), newlyVisible};
}

void requireCameras(const ReferenceCameras& cameras, const EyeFrame& frame, const char* which) {
  const std::size_t layers = cameras.view.size();
  if (layers == 0 || cameras.projection.size() != layers || cameras.segments.size() != layers || layers > 256)
    throw std::invalid_argument(std::string("temporal flicker: the ") + which +
                                " frame's cameras need one view, projection and segment per layer (1..256)");
  if (cameras.layerOfPixel.empty()) return;
  if (frame.reference && cameras.layerOfPixel.size() != frame.reference->pixelCount())
    throw std::invalid_argument(std::string("temporal flicker: the ") + which +
                                " frame's layer per pixel does not match the image size");
  for (std::uint8_t layer : cameras.layerOfPixel)
    if (layer >= layers)
      throw std::invalid_argument(std::string("temporal flicker: the ") + which + " frame names a layer it has no camera for");
}

// The layer whose segment holds inverse depth u, else the one whose segment lies nearest (as the per-layer
// reference chooses for a depth no segment holds).
std::size_t layerFor(const std::vector<DisparityMapSegment>& segments, double u) {
  std::size_t best = 0;
  double bestDistance = INFINITY;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const double distance = u < segments[k].inverseDepthBegin ? segments[k].inverseDepthBegin - u
                            : u > segments[k].inverseDepthEnd ? u - segments[k].inverseDepthEnd
                                                              : 0.0;
    if (distance < bestDistance) best = k, bestDistance = distance;
  }
  return best;
}

}  // namespace

FlickerStats temporalFlicker(const EyeFrame& current, const EyeFrame& previous, const gpu::EyeMotion& motion,
                             const std::vector<std::uint8_t>& halo, const std::vector<std::uint8_t>& disocclusion) {
  const int width = current.reference ? int(current.reference->width) : 0;
  const int height = current.reference ? int(current.reference->height) : 0;
  return flicker(current, previous, halo, disocclusion, [&](std::size_t, gpu::vec2 pixel, float inverseDepth) {
    return gpu::reprojectToPrevious(motion, pixel, inverseDepth, width, height);
  });
}

FlickerStats temporalFlicker(const EyeFrame& current, const EyeFrame& previous, const ReferenceCameras& currentCameras,
                             const ReferenceCameras& previousCameras, const std::vector<std::uint8_t>& halo,
                             const std::vector<std::uint8_t>& disocclusion) {
  requireCameras(currentCameras, current, "current");
  requireCameras(previousCameras, previous, "previous");
  const std::size_t previousLayers = previousCameras.view.size();
  std::vector<gpu::EyeMotion> motions;  // [current layer * previousLayers + previous layer]
  for (std::size_t k = 0; k < currentCameras.view.size(); ++k)
    for (std::size_t j = 0; j < previousLayers; ++j)
      motions.push_back(eyeMotion(currentCameras.view[k], currentCameras.projection[k], previousCameras.view[j],
                                  previousCameras.projection[j]));
  const int width = current.reference ? int(current.reference->width) : 0;
  const int height = current.reference ? int(current.reference->height) : 0;
  const std::vector<std::uint8_t>& previousLayer = previousCameras.layerOfPixel;
  // Whether the previous reference shows layer j's rendering at position `was` (its nearest texel).
  auto shows = [&](std::size_t j, gpu::vec3 was) {
    if (previousLayer.empty()) return j == 0;
    const int x = int(std::floor(was.x)), y = int(std::floor(was.y));
    if (x < 0 || y < 0 || x >= width || y >= height) return false;
    return previousLayer[std::size_t(y) * std::size_t(width) + std::size_t(x)] == j;
  };
  return flicker(current, previous, halo, disocclusion, [&](std::size_t i, gpu::vec2 pixel, float inverseDepth) {
    const std::size_t k = currentCameras.layerOfPixel.empty() ? 0 : currentCameras.layerOfPixel[i];
    const gpu::EyeMotion* fromLayer = &motions[k * previousLayers];
    const gpu::vec3 first = gpu::reprojectToPrevious(fromLayer[0], pixel, inverseDepth, width, height);
    if (previousLayers == 1 || first.z < 0.0f) return first;
    // The previous inverse depth is the same under every previous layer's camera; the layer whose segment holds
    // it rendered the surface exactly, where the previous reference shows that layer. Elsewhere (depth edges
    // across segments, pixels no layer claimed) the layer the previous reference does show there.
    const std::size_t primary = layerFor(previousCameras.segments, double(first.z));
    const gpu::vec3 was = gpu::reprojectToPrevious(fromLayer[primary], pixel, inverseDepth, width, height);
    if (shows(primary, was)) return was;
    for (std::size_t j = 0; j < previousLayers; ++j) {
      if (j == primary) continue;
      const gpu::vec3 other = gpu::reprojectToPrevious(fromLayer[j], pixel, inverseDepth, width, height);
      if (shows(j, other)) return other;
    }
    return was;
  });
}

}  // namespace s3d::stereo
