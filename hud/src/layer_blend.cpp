#include "s3d/hud/layer_blend.h"

#include <algorithm>

#include "s3d/hud/hud_pass_shared.h"

namespace s3d::hud {
namespace {

// blendLayer's per-pixel rule with the shared math; counts as blendLayer counts.
void blendPixel(std::uint8_t* target, const std::uint8_t* source, bool behindWeapon, BlendCounts& counts) {
  if (source[3] == 0) return;
  const float opacity = gpu::hudOpacity(float(source[3]), float(target[3]), behindWeapon ? 1 : 0);
  if (behindWeapon && target[3] < 255) ++counts.fadedPixels;
  if (opacity <= 0.0f) return;
  ++counts.drawnPixels;
  for (int c = 0; c < 3; ++c) target[c] = std::uint8_t(gpu::hudBlendChannel(float(target[c]), float(source[c]), opacity));
}

}  // namespace

BlendCounts compositeLayer(ImageRGBA8& eye, const ImageRGBA8& layer, int x, int y, bool behindWeapon) {
  BlendCounts counts;
  const long x0 = std::max(0L, long(x)), x1 = std::min(long(eye.width), long(x) + long(layer.width));
  const long y0 = std::max(0L, long(y)), y1 = std::min(long(eye.height), long(y) + long(layer.height));
  for (long ey = y0; ey < y1; ++ey)
    for (long ex = x0; ex < x1; ++ex)
      blendPixel(eye.at(std::uint32_t(ex), std::uint32_t(ey)),
                 layer.at(std::uint32_t(ex - x), std::uint32_t(ey - y)), behindWeapon, counts);
  return counts;
}

}  // namespace s3d::hud
