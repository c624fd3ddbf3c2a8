#include "s3d/stereo/disparity_map.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace s3d::stereo {
namespace {

// A knot before its mapped value is known. Inverse depths are float divisions, as the shader's u = 1 / d, so a
// fixed knot's depth maps onto itself bit for bit.
struct Knot {
  double inverseDepth = 0.0;
  double pixelsFarther = 0.0;  // finite pixels with a larger depth (exact at bin edges)
  bool fixed = false;          // maps onto itself
};

// Finite pixels farther than bin edge `edgeBin`, from the near end: bins hold [edge b, edge b+1).
double fartherThanEdge(const DepthRange& range, std::uint32_t edgeBin) {
  double nearer = 0.0;
  for (std::uint32_t b = 0; b < edgeBin; ++b) nearer += range.bins[b];
  return double(range.finitePixels()) - nearer;
}

// The fixed points: the sky (inverse depth 0) if any, the farthest finite depth (fixed without sky), the nearest,
// and the zero-parallax plane when it lies between them.
std::vector<Knot> fixedKnots(const DepthRange& range, float zeroParallaxDistance) {
  const double farthestInverse = 1.0f / range.farthest, nearestInverse = 1.0f / range.nearest;
  const bool sky = range.skyPixels > 0;
  std::vector<Knot> knots;
  if (sky) knots.push_back({0.0, 0.0, true});
  knots.push_back({farthestInverse, 0.0, !sky});
  if (nearestInverse > farthestInverse) knots.push_back({nearestInverse, double(range.finitePixels()), true});
  const double zeroParallaxInverse = 1.0f / zeroParallaxDistance;
  if (zeroParallaxInverse > knots.front().inverseDepth && zeroParallaxInverse < knots.back().inverseDepth) {
    // Its farther count between the bin edges around it, linearly: any value between them keeps F monotonic.
    const double depth = zeroParallaxDistance;
    std::uint32_t edge = 1;
    while (edge < range.bins.size() && depthBinLowerEdge(edge) <= depth) ++edge;
    const double below = depthBinLowerEdge(edge - 1), above = depthBinLowerEdge(edge);
    const double fraction = std::clamp((depth - below) / (above - below), 0.0, 1.0);
    const double farther = fartherThanEdge(range, edge - 1) +
                           fraction * (fartherThanEdge(range, edge) - fartherThanEdge(range, edge - 1));
    knots.push_back({zeroParallaxInverse, farther, true});
  }
  return knots;
}

// A knot at bin edge `edgeBin`, where its farther count is exact, if the edge lies inside the finite range.
void addEdgeKnot(std::vector<Knot>& knots, const DepthRange& range, std::uint32_t edgeBin) {
  const double edgeDepth = depthBinLowerEdge(edgeBin);
  if (edgeDepth > double(range.nearest) && edgeDepth < double(range.farthest))
    knots.push_back({1.0f / float(edgeDepth), fartherThanEdge(range, edgeBin), false});
}

// Both edges of the widest empty runs of bins, the gaps the map should compress (without knots at their edges a
// segment would mix a gap with the populated depths beside it); one knot stays free for the pixel shares.
void addGapKnots(std::vector<Knot>& knots, const DepthRange& range) {
  const std::uint32_t nearestBin = gpu::depthHistogramBin(std::bit_cast<std::uint32_t>(range.nearest));
  const std::uint32_t farthestBin = gpu::depthHistogramBin(std::bit_cast<std::uint32_t>(range.farthest));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> gaps;  // [first empty bin, one past the last)
  for (std::uint32_t b = nearestBin + 1; b < farthestBin; ++b) {
    if (range.bins[b] != 0) continue;
    std::uint32_t end = b;
    while (end < farthestBin && range.bins[end] == 0) ++end;
    gaps.push_back({b, end});
    b = end;
  }
  std::stable_sort(gaps.begin(), gaps.end(),
                   [](const auto& a, const auto& b) { return a.second - a.first > b.second - b.first; });
  for (const auto& [first, end] : gaps) {
    if (int(knots.size()) + 2 > S3D_DISPARITY_MAP_KNOTS - 1) break;
    addEdgeKnot(knots, range, first);
    addEdgeKnot(knots, range, end);
  }
}

// The remaining knots at the bin edges where the finite pixels' cumulative share crosses equal steps.
void addShareKnots(std::vector<Knot>& knots, const DepthRange& range) {
  const double finite = double(range.finitePixels());
  const int interior = S3D_DISPARITY_MAP_KNOTS - int(knots.size());
  double nearer = 0.0;
  int step = 1;
  for (std::uint32_t b = 0; b + 1 < range.bins.size() && step <= interior; ++b) {
    nearer += range.bins[b];
    if (nearer < finite * double(step) / double(interior + 1)) continue;
    while (step <= interior && nearer >= finite * double(step) / double(interior + 1)) ++step;
    addEdgeKnot(knots, range, b + 1);
  }
}

// Sorted by inverse depth; knots closer than float resolution would give a zero-length segment: the first is
// kept (fixed ones win).
std::vector<Knot> distinctKnots(std::vector<Knot> knots) {
  std::sort(knots.begin(), knots.end(), [](const Knot& a, const Knot& b) { return a.inverseDepth < b.inverseDepth; });
  std::vector<Knot> distinct;
  for (const Knot& knot : knots) {
    if (!distinct.empty() && float(knot.inverseDepth) <= float(distinct.back().inverseDepth)) {
      if (knot.fixed) distinct.back() = knot;
      continue;
    }
    distinct.push_back(knot);
  }
  return distinct;
}

// Per region between consecutive fixed knots, each segment's share of the region's disparity: its share of the
// inverse-depth span t times the stretch r = (1 - s) + s (pixel share / t share), r clamped to
// [1 - s, kMaxMappingStretch], then normalized so the region's ends stay put. r > 0 everywhere: w rises strictly;
// empty segments shrink to 1 - s of their linear share, populated ones grow by at most the cap.
std::vector<double> mappedInverseDepths(const std::vector<Knot>& knots, float strength) {
  std::vector<double> mapped(knots.size());
  std::size_t begin = 0;
  for (std::size_t end = 1; end < knots.size(); ++end) {
    if (!knots[end].fixed && end + 1 < knots.size()) continue;
    const Knot& lo = knots[begin];
    const Knot& hi = knots[end];
    const double span = hi.inverseDepth - lo.inverseDepth, pixels = hi.pixelsFarther - lo.pixelsFarther;
    std::vector<double> weight(end - begin);
    double total = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      const double spanShare = (knots[i + 1].inverseDepth - knots[i].inverseDepth) / span;
      const double pixelShare =
          pixels > 0.0 ? std::max(knots[i + 1].pixelsFarther - knots[i].pixelsFarther, 0.0) / pixels : spanShare;
      const double stretch = std::clamp((1.0 - double(strength)) + double(strength) * pixelShare / spanShare,
                                        1.0 - double(strength), double(kMaxMappingStretch));
      weight[i - begin] = stretch * spanShare;
      total += weight[i - begin];
    }
    mapped[begin] = lo.inverseDepth;
    for (std::size_t i = begin; i < end; ++i) mapped[i + 1] = mapped[i] + span * weight[i - begin] / total;
    mapped[end] = hi.inverseDepth;
    begin = end;
  }
  return mapped;
}

gpu::DisparityMapConstants mapConstants(const std::vector<Knot>& knots, const std::vector<double>& mapped) {
  gpu::DisparityMapConstants map{};
  map.knotCount = int(knots.size());
  for (std::size_t i = 0; i < knots.size(); ++i) {
    map.inverseDepth[i] = float(knots[i].inverseDepth);
    map.mapped[i] = float(mapped[i]);
  }
  // Float rounding must not make w stall or fall: each mapped value at least one step above the previous.
  for (int i = 1; i < map.knotCount; ++i)
    map.mapped[i] = std::max(map.mapped[i], std::nextafter(map.mapped[i - 1], std::numeric_limits<float>::infinity()));
  for (int i = 0; i + 1 < map.knotCount; ++i)
    map.slope[i] = float((double(map.mapped[i + 1]) - double(map.mapped[i])) /
                         (double(map.inverseDepth[i + 1]) - double(map.inverseDepth[i])));
  map.slope[map.knotCount - 1] = 1.0f;  // beyond the last knot (the shader uses 1 there; stated for the segments)
  return map;
}

}  // namespace

const char* disparityMappingName(DisparityMapping mapping) {
  return mapping == DisparityMapping::Linear ? "linear" : "nonlinear";
}

DisparityMapping parseDisparityMapping(const std::string& name) {
  if (name == "linear") return DisparityMapping::Linear;
  if (name == "nonlinear") return DisparityMapping::Nonlinear;
  throw std::invalid_argument("unknown disparity mapping '" + name + "' (choices: linear, nonlinear)");
}

gpu::DisparityMapConstants identityDisparityMap() { return gpu::DisparityMapConstants{}; }

gpu::DisparityMapConstants nonlinearDisparityMap(const DepthRange& range, float zeroParallaxDistance, float strength) {
  if (!(strength >= 0.0f && strength <= kMaxMappingStrength))
    throw std::invalid_argument("disparity mapping strength must be in [0, " + std::to_string(kMaxMappingStrength) +
                                "] (got " + std::to_string(strength) + ")");
  if (!(zeroParallaxDistance > 0.0f))
    throw std::invalid_argument("disparity mapping: the zero-parallax distance must be positive");
  if (!range.hasFinite() || range.bins.empty()) return identityDisparityMap();
  if (!(1.0f / range.nearest > 1.0f / range.farthest) && range.skyPixels == 0) return identityDisparityMap();
  // Interior knots at bin edges: first the gaps' edges, then the pixel shares.
  std::vector<Knot> knots = fixedKnots(range, zeroParallaxDistance);
  addGapKnots(knots, range);
  addShareKnots(knots, range);
  const std::vector<Knot> distinct = distinctKnots(std::move(knots));
  if (distinct.size() < 2) return identityDisparityMap();
  return mapConstants(distinct, mappedInverseDepths(distinct, strength));
}

gpu::DisparityMapConstants disparityMapFor(DisparityMapping mapping, const DepthRange& range,
                                           float zeroParallaxDistance) {
  return mapping == DisparityMapping::Linear ? identityDisparityMap()
                                             : nonlinearDisparityMap(range, zeroParallaxDistance);
}

void mapDepthReference(DepthImage& linearDepth, const gpu::DisparityMapConstants& map) {
  for (float& depth : linearDepth.pixels) depth = gpu::mappedDepth(map, depth);
}

DepthImage mappedDepthImage(DepthImage linearDepth, const gpu::DisparityMapConstants& map) {
  mapDepthReference(linearDepth, map);
  return linearDepth;
}

std::vector<DisparityMapSegment> disparityMapSegments(const gpu::DisparityMapConstants& map) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (map.knotCount < 2) return {{0.0, kInfinity, 1.0, 0.0}};
  std::vector<DisparityMapSegment> segments;
  for (int i = 0; i + 1 < map.knotCount; ++i) {
    const double slope = double(map.slope[i]);
    segments.push_back({i == 0 ? 0.0 : double(map.inverseDepth[i]),
                        i + 2 == map.knotCount ? kInfinity : double(map.inverseDepth[i + 1]), slope,
                        double(map.mapped[i]) - slope * double(map.inverseDepth[i])});
  }
  return segments;
}

}  // namespace s3d::stereo
