#include "s3d/stereo/temporal.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

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

}  // namespace

FlickerStats temporalFlicker(const EyeFrame& current, const EyeFrame& previous, const gpu::EyeMotion& motion,
                             const std::vector<std::uint8_t>& halo, const std::vector<std::uint8_t>& disocclusion) {
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
                                  : gpu::reprojectToPrevious(motion, {float(x) + 0.5f, float(y) + 0.5f}, inverseDepth,
                                                             int(width), int(height));
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

}  // namespace s3d::stereo
