#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "s3d/stereo/forward.h"
#include "s3d/stereo/previous_fill.h"

namespace s3d::stereo {
namespace {

// A hole pixel's nearest covered neighbours in its row (within the edge search): the farther one's depth is a
// guess of the depth behind the occluder (0: nothing covered nearby); the nearer one's is the occluder's when the
// two are different surfaces (else 0).
struct HoleEdges {
  float background = 0.0f;
  float occluder = 0.0f;
};

HoleEdges holeEdges(const std::vector<std::uint32_t>& keys, int x, int y, const gpu::PreviousFillConstants& c) {
  const std::size_t row = std::size_t(y) * std::size_t(c.width);
  std::uint32_t found[2] = {S3D_FORWARD_EMPTY, S3D_FORWARD_EMPTY};
  for (int s = 0; s < 2; ++s)
    for (int i = 1; i <= c.edgeSearchPx; ++i) {
      const int column = x + (s == 0 ? -i : i);
      if (column < 0 || column >= c.width) break;
      const std::uint32_t key = keys[row + std::size_t(column)];
      if (key == S3D_FORWARD_EMPTY) continue;
      found[s] = key;
      break;
    }
  const gpu::vec2 edges = gpu::previousFillEdges(found[0], found[1]);
  return {edges.x, edges.y};
}

// The previous eye's colour (0..1) around `position` over the texels showing the surface of inverse depth
// `expected`, weighted bilinearly; weightSum 0 when none does.
gpu::vec4 previousSample(const EyeHistory& previous, gpu::vec2 position, float expected,
                         const gpu::PreviousFillConstants& c, float& weightSum) {
  const gpu::ivec2 topLeft = gpu::bilinearTopLeft(position);
  const gpu::vec4 weights = gpu::bilinearWeights(position);
  gpu::vec4 sum(0.0f);
  weightSum = 0.0f;
  for (int tap = 0; tap < 4; ++tap) {
    const gpu::ivec2 t = topLeft + gpu::ivec2(tap & 1, tap >> 1);
    const float w = weights[tap];
    if (!(w >= S3D_REPROJECTION_MIN_WEIGHT) || !gpu::previousFillInsideEye(c, t)) continue;
    if (!gpu::sameSurface(expected, gpu::inverseDepthOf(*previous.depth.at(std::uint32_t(t.x), std::uint32_t(t.y)))))
      continue;
    const std::uint8_t* texel = previous.color.at(std::uint32_t(t.x), std::uint32_t(t.y));
    if (!(float(texel[3]) / 255.0f >= S3D_PREVIOUS_FILL_WORLD_ALPHA)) continue;
    sum += w * (gpu::vec4(texel[0], texel[1], texel[2], texel[3]) / 255.0f);
    weightSum += w;
  }
  return sum;
}

}  // namespace

gpu::PreviousFillConstants makePreviousFillConstants(const gpu::ForwardConstants& forward, const gpu::EyeMotion& motion,
                                                     bool hasHistory) {
  gpu::PreviousFillConstants c{};
  c.motion = motion;
  c.width = forward.width;
  c.height = forward.height;
  c.cropBegin = forward.cropBegin;
  c.cropEnd = forward.cropEnd;
  c.edgeSearchPx = forward.fillSearchPx;
  c.hasHistory = hasHistory ? 1 : 0;
  return c;
}

EyeHistory fillFromPreviousFrameReference(ImageRGBA8& eye, const std::vector<std::uint32_t>& keys,
                                          const EyeHistory* previous, const gpu::PreviousFillConstants& c,
                                          PreviousFillCounts* counts) {
  if (int(eye.width) != c.width || int(eye.height) != c.height ||
      keys.size() != std::size_t(c.width) * std::size_t(c.height))
    throw std::invalid_argument("previous-frame fill: the eye or its keys do not match the constants");
  const bool useHistory = c.hasHistory != 0;
  if (useHistory && (!previous || int(previous->color.width) != c.width || int(previous->color.height) != c.height ||
                     int(previous->depth.width) != c.width || int(previous->depth.height) != c.height))
    throw std::invalid_argument("previous-frame fill: the previous frame's eye does not match the constants");
  EyeHistory history{ImageRGBA8(eye.width, eye.height), DepthImage(eye.width, eye.height)};
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      std::uint8_t* out = eye.at(std::uint32_t(x), std::uint32_t(y));
      std::uint8_t* kept = history.color.at(std::uint32_t(x), std::uint32_t(y));
      float& depth = *history.depth.at(std::uint32_t(x), std::uint32_t(y));
      if (x < c.cropBegin || x >= c.cropEnd) {
        kept[0] = kept[1] = kept[2] = 0, kept[3] = 255;
        depth = 0.0f;
        continue;
      }
      const std::uint32_t key = keys[std::size_t(y) * std::size_t(c.width) + std::size_t(x)];
      if (key != S3D_FORWARD_EMPTY) {
        std::copy_n(out, 4, kept);
        depth = gpu::forwardKeyLinearDepth(key);
        continue;
      }
      const HoleEdges edges = holeEdges(keys, x, y, c);
      const float background = edges.background;
      depth = background;
      if (counts) ++counts->holePixels;
      if (useHistory) {
        float q = gpu::inverseDepthOf(background);
        const gpu::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
        for (int k = 0; k < S3D_PREVIOUS_FILL_ITERATIONS && q >= 0.0f; ++k) {
          const gpu::vec3 was = gpu::reprojectToPrevious(c.motion, centre, q, c.width, c.height);
          if (was.z < 0.0f) break;
          float weightSum = 0.0f;
          const gpu::vec4 sum = previousSample(*previous, {was.x, was.y}, was.z, c, weightSum);
          if (weightSum > 0.0f && gpu::behindOccluder(q, edges.occluder)) {
            const gpu::vec4 color = sum / weightSum;
            for (int i = 0; i < 4; ++i) out[i] = std::uint8_t(std::lround(std::clamp(color[i], 0.0f, 1.0f) * 255.0f));
            depth = q > 0.0f ? 1.0f / q : S3D_INFINITY;
            if (counts) ++counts->filledFromPrevious;
            break;
          }
          const gpu::ivec2 t(int(std::floor(was.x)), int(std::floor(was.y)));
          if (!gpu::previousFillInsideEye(c, t)) break;
          const float previousInverse = gpu::inverseDepthOf(*previous->depth.at(std::uint32_t(t.x), std::uint32_t(t.y)));
          const float previousAlpha = float(previous->color.at(std::uint32_t(t.x), std::uint32_t(t.y))[3]) / 255.0f;
          if (previousInverse < 0.0f || !(previousAlpha >= S3D_PREVIOUS_FILL_WORLD_ALPHA)) break;
          q = gpu::reprojectToCurrent(c.motion, gpu::vec2(float(t.x) + 0.5f, float(t.y) + 0.5f), previousInverse,
                                      c.width, c.height).z;
        }
      }
      std::copy_n(out, 4, kept);
    }
  return history;
}

ForwardWithHistory synthesizeForwardWithPreviousFrameReference(const ImageRGBA8& center, const DepthImage& linearDepth,
                                                               const gpu::ForwardConstants& forward,
                                                               const std::array<gpu::EyeMotion, 2>& motion,
                                                               const std::array<EyeHistory, 2>* previous) {
  ForwardWithHistory result;
  result.eyes = synthesizeForwardReference(center, linearDepth, forward);
  for (int e = 0; e < 2; ++e) {
    std::vector<std::uint32_t> keys;
    keys.reserve(std::size_t(forward.width) * std::size_t(forward.height));
    for (int y = 0; y < forward.height; ++y) {
      const std::vector<std::uint32_t> row = forwardSplatRow(linearDepth, y, e == 0 ? 1.0f : -1.0f, forward);
      keys.insert(keys.end(), row.begin(), row.end());
    }
    ImageRGBA8& eye = e == 0 ? result.eyes.left : result.eyes.right;
    const gpu::PreviousFillConstants c = makePreviousFillConstants(forward, motion[std::size_t(e)], previous != nullptr);
    result.history[std::size_t(e)] = fillFromPreviousFrameReference(
        eye, keys, previous ? &(*previous)[std::size_t(e)] : nullptr, c, &result.counts[std::size_t(e)]);
  }
  return result;
}

}  // namespace s3d::stereo
