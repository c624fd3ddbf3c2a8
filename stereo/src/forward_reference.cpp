#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "row_sampling.h"
#include "s3d/number_text.h"
#include "s3d/stereo/forward.h"

namespace s3d::stereo {
namespace {

using detail::sampleRow;

float depthAt(const DepthImage& depth, int x, int y) { return *depth.at(std::uint32_t(x), std::uint32_t(y)); }

// A known pixel's eye position, and whether it and its right neighbour are one surface.
struct Placed {
  bool known;
  float position;
};

Placed place(const DepthImage& depth, int x, int y, float direction, const gpu::ForwardConstants& c) {
  if (x < 0 || x >= c.width) return {false, 0.0f};
  const float d = depthAt(depth, x, y);
  if (!gpu::forwardKnownDepth(d)) return {false, 0.0f};
  return {true, gpu::forwardPosition(c, x, direction, d)};
}

bool connectedRight(const DepthImage& depth, int x, int y, float direction, const gpu::ForwardConstants& c) {
  const Placed here = place(depth, x, y, direction, c), next = place(depth, x + 1, y, direction, c);
  return here.known && next.known && gpu::forwardConnected(here.position, next.position);
}

void splat(std::vector<std::uint32_t>& keys, float direction, float from, float to, float depth, int source) {
  const int end = std::min(gpu::forwardFirstColumn(to, direction), int(keys.size()));
  for (int column = std::max(gpu::forwardFirstColumn(from, direction), 0); column < end; ++column)
    keys[std::size_t(column)] = std::min(keys[std::size_t(column)], gpu::forwardKey(depth, source, column));
}

// How many pixels from `first` in steps of `step` (up to S3D_FORWARD_FILL_TAPS, before column `stop`) lie on
// the surface of parallax `parallax` (within 1 px).
int surfaceRun(const DepthImage& depth, int y, int first, int step, int stop, float parallax,
               const gpu::ForwardConstants& c) {
  int count = 0;
  for (int x = first; count < S3D_FORWARD_FILL_TAPS && x >= 0 && x < c.width && x != stop; x += step) {
    const float d = depthAt(depth, x, y);
    if (!gpu::forwardKnownDepth(d) || std::abs(gpu::forwardParallaxPx(c, d) - parallax) > 1.0f) break;
    ++count;
  }
  return count;
}

// A hole pixel (forward_shared.h): the background between the hole's two edges in the center row, else the
// surface behind the farther edge.
ForwardSample fillHole(const DepthImage& depth, const std::vector<std::uint32_t>& keys, int column, int y,
                       const gpu::ForwardConstants& c) {
  int left = -1, right = -1;
  for (int i = 1; i <= c.fillSearchPx && left < 0 && column - i >= 0; ++i)
    if (keys[std::size_t(column - i)] != S3D_FORWARD_EMPTY) left = column - i;
  for (int i = 1; i <= c.fillSearchPx && right < 0 && column + i < c.width; ++i)
    if (keys[std::size_t(column + i)] != S3D_FORWARD_EMPTY) right = column + i;
  if (left < 0 && right < 0) return {0.0f, column, 1, 1};  // nothing lands near: the center pixel itself
  if (left >= 0 && right >= 0) {
    // Center pixels between the edges' sources that lie behind both edges were hidden in this eye: a gap
    // between two occluders shows the background the gap showed, not an occluder.
    const int leftSource = gpu::forwardKeySource(keys[std::size_t(left)], left);
    const int rightSource = gpu::forwardKeySource(keys[std::size_t(right)], right);
    const int low = std::min(leftSource, rightSource), high = std::max(leftSource, rightSource);
    float farthest = std::max(gpu::forwardParallaxPx(c, depthAt(depth, leftSource, y)),
                              gpu::forwardParallaxPx(c, depthAt(depth, rightSource, y))) + 1.0f;
    int background = -1;
    for (int x = low + 1; x < high && x <= low + c.fillSearchPx; ++x) {
      const float d = depthAt(depth, x, y);
      if (gpu::forwardKnownDepth(d) && gpu::forwardParallaxPx(c, d) > farthest) {
        farthest = gpu::forwardParallaxPx(c, d);
        background = x;
      }
    }
    if (background >= 0) return {0.0f, background, surfaceRun(depth, y, background, 1, high, farthest, c), 1};
  }
  const bool useRight = left < 0 || (right >= 0 && gpu::forwardKeyDepth(keys[std::size_t(right)]) >
                                                       gpu::forwardKeyDepth(keys[std::size_t(left)]));
  const int edge = useRight ? right : left;
  const int source = gpu::forwardKeySource(keys[std::size_t(edge)], edge);
  const int away = useRight ? 1 : -1;
  const float edgeParallax = gpu::forwardParallaxPx(c, depthAt(depth, source, y));
  const int first = source + away * S3D_FORWARD_FILL_SKIP;
  const int count = surfaceRun(depth, y, first, away, -1, edgeParallax, c);
  if (count == 0) return {0.0f, source, 1, 1};
  return {0.0f, first, count, away};
}

}  // namespace

gpu::ForwardConstants makeForwardConstants(const StereoParameters& p, std::uint32_t width, std::uint32_t height) {
  const gpu::StereoConstants seed = makeSeedConstants(p, width, height);  // validates; the seed's crop
  gpu::ForwardConstants c{};
  c.maxSeparation = p.maxSeparation;
  c.zeroParallaxDistance = p.zeroParallaxDistance;
  c.maxParallaxPx = p.maxSeparation * float(width);
  c.cropBegin = seed.cropBegin;
  c.cropEnd = seed.cropEnd;
  c.width = int(width);
  c.height = int(height);
  c.fillSearchPx = int(std::ceil(2.0f * c.maxParallaxPx)) + 2;
  if (c.maxParallaxPx + 2.0f > float(S3D_FORWARD_OFFSET_BIAS - 1))
    throw std::invalid_argument("forward stereo method: a displacement of " + numberText(c.maxParallaxPx) +
                                " px is beyond its limit of " + std::to_string(S3D_FORWARD_OFFSET_BIAS - 3) + " px");
  return c;
}

std::vector<std::uint32_t> forwardSplatRow(const DepthImage& linearDepth, int y, float direction,
                                           const gpu::ForwardConstants& c) {
  std::vector<std::uint32_t> keys(std::size_t(c.width), S3D_FORWARD_EMPTY);
  for (int x = 0; x < c.width; ++x) {
    const Placed here = place(linearDepth, x, y, direction, c);
    if (!here.known) continue;
    const float depth = depthAt(linearDepth, x, y);
    const Placed previous = place(linearDepth, x - 1, y, direction, c);
    const Placed next = place(linearDepth, x + 1, y, direction, c);
    if (!(previous.known && gpu::forwardConnected(previous.position, here.position)))
      splat(keys, direction, here.position - 0.5f, here.position, depth, x);  // open left end: half a pixel
    if (next.known && gpu::forwardConnected(here.position, next.position))
      splat(keys, direction, here.position, next.position, std::min(depth, depthAt(linearDepth, x + 1, y)), x);
    else
      splat(keys, direction, here.position, here.position + 0.5f, depth, x);  // open right end
  }
  return keys;
}

std::vector<ForwardSample> forwardRowSamples(const DepthImage& linearDepth, int y, float direction,
                                             const gpu::ForwardConstants& c) {
  const std::vector<std::uint32_t> keys = forwardSplatRow(linearDepth, y, direction, c);
  std::vector<ForwardSample> samples(std::size_t(c.width));
  for (int x = 0; x < c.width; ++x) {
    const std::uint32_t key = keys[std::size_t(x)];
    if (key == S3D_FORWARD_EMPTY) {
      samples[std::size_t(x)] = fillHole(linearDepth, keys, x, y, c);
      continue;
    }
    const int source = gpu::forwardKeySource(key, x);
    const float position = gpu::forwardPosition(c, source, direction, depthAt(linearDepth, source, y));
    const bool connected = connectedRight(linearDepth, source, y, direction, c);
    const float nextPosition =
        connected ? gpu::forwardPosition(c, source + 1, direction, depthAt(linearDepth, source + 1, y)) : 0.0f;
    samples[std::size_t(x)].position = gpu::forwardSourcePosition(x, source, position, connected, nextPosition);
  }
  return samples;
}

StereoPair synthesizeForwardReference(const ImageRGBA8& center, const DepthImage& linearDepth,
                                      const gpu::ForwardConstants& c) {
  requireSameSize(center, linearDepth, "stereo pass (color vs depth)");
  if (int(center.width) != c.width || int(center.height) != c.height)
    throw std::invalid_argument("forward stereo pass: constants were made for another image size");
  StereoPair pair{ImageRGBA8(center.width, center.height), ImageRGBA8(center.width, center.height)};
  for (int y = 0; y < c.height; ++y) {
    for (auto [eye, direction] : {std::pair{&pair.left, 1.0f}, std::pair{&pair.right, -1.0f}}) {
      const std::vector<ForwardSample> samples = forwardRowSamples(linearDepth, y, direction, c);
      for (int x = 0; x < c.width; ++x) {
        std::uint8_t* out = eye->at(std::uint32_t(x), std::uint32_t(y));
        const ForwardSample& sample = samples[std::size_t(x)];
        if (x < c.cropBegin || x >= c.cropEnd) {  // cropped edges, as in the seed
          std::fill(out, out + 3, std::uint8_t(0));
          out[3] = 255;
        } else if (sample.fillCount == 0) {
          sampleRow(center, y, sample.position, out);
        } else {
          float sum[4] = {0, 0, 0, 0};
          for (int k = 0; k < sample.fillCount; ++k) {
            const std::uint8_t* texel = center.at(std::uint32_t(sample.fillFirst + k * sample.fillStep), std::uint32_t(y));
            for (int channel = 0; channel < 4; ++channel) sum[channel] += float(texel[channel]) / 255.0f;
          }
          for (int channel = 0; channel < 4; ++channel)
            out[channel] = std::uint8_t(
                std::lround(std::clamp(sum[channel] / float(sample.fillCount), 0.0f, 1.0f) * 255.0f));
        }
      }
    }
  }
  return pair;
}

}  // namespace s3d::stereo
