#include "s3d/stereo/temporal.h"

#include <cstdlib>
#include <stdexcept>

namespace s3d::stereo {
namespace {

struct Sum {
  double levels = 0.0;
  std::uint64_t pixels = 0;
  void add(double value) { levels += value, ++pixels; }
  FlickerRegion region() const { return {pixels ? levels / double(pixels) : 0.0, pixels}; }
};

}  // namespace

FlickerStats temporalFlicker(const ImageRGBA8& synthesized, const ImageRGBA8& previousSynthesized,
                             const ImageRGBA8& reference, const ImageRGBA8& previousReference,
                             std::uint32_t cropColumns, const std::vector<std::uint8_t>& halo,
                             const std::vector<std::uint8_t>& disocclusion) {
  requireSameSize(synthesized, previousSynthesized, "temporal flicker (synthesized frames)");
  requireSameSize(synthesized, reference, "temporal flicker (synthesized vs reference)");
  requireSameSize(reference, previousReference, "temporal flicker (reference frames)");
  const std::size_t count = synthesized.pixelCount();
  if ((!halo.empty() && halo.size() != count) || (!disocclusion.empty() && disocclusion.size() != count))
    throw std::invalid_argument("temporal flicker: a region mask does not match the image size");
  Sum all, haloSum, disocclusionSum;
  const std::uint32_t width = synthesized.width;
  for (std::uint32_t y = 0; y < synthesized.height; ++y)
    for (std::uint32_t x = cropColumns; x + cropColumns < width; ++x) {
      const std::size_t i = std::size_t(y) * width + x;
      int levels = 0;
      for (int c = 0; c < 3; ++c) {
        const std::size_t k = i * 4 + std::size_t(c);
        const int changeSynthesized = int(synthesized.pixels[k]) - int(previousSynthesized.pixels[k]);
        const int changeReference = int(reference.pixels[k]) - int(previousReference.pixels[k]);
        levels += std::abs(changeSynthesized - changeReference);
      }
      const double value = double(levels) / 3.0;
      all.add(value);
      if (!halo.empty() && halo[i]) haloSum.add(value);
      if (!disocclusion.empty() && disocclusion[i]) disocclusionSum.add(value);
    }
  return {all.region(), haloSum.region(), disocclusionSum.region()};
}

}  // namespace s3d::stereo
