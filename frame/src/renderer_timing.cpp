#include "s3d/frame/renderer_timing.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "s3d/stereo/synthesis.h"

namespace s3d::frame {

std::optional<double> medianOf(const std::vector<std::optional<double>>& samples) {
  std::vector<double> present;
  for (const std::optional<double>& sample : samples)
    if (sample) present.push_back(*sample);
  return stereo::medianMs(present);
}

std::pair<std::optional<double>, std::vector<renderer::PassTiming>> timeFrames(renderer::DeferredRenderer& deferred,
                                                                               const renderer::ViewMatrices& view,
                                                                               int repeat, const renderer::ShadeMask& mask,
                                                                               std::chrono::milliseconds warmUp) {
  std::vector<std::optional<double>> totals;
  std::vector<renderer::PassTiming> order;
  std::map<std::string, std::vector<double>> passTimes;
  // Untimed frames for at least `warmUp` first: a GPU that idled while the host computed metrics ramps its
  // clocks back up (a GPU timed a reference eye at several times its warm time after a short warm-up).
  const auto warmUpStart = std::chrono::steady_clock::now();
  do (void)deferred.render(view, mask);
  while (std::chrono::steady_clock::now() - warmUpStart < warmUp);
  for (int run = 0; run < repeat; ++run) {
    renderer::FrameTimings timings = deferred.render(view, mask);
    totals.push_back(timings.totalGpuMs);
    if (run == 0) order = timings.passes;
    for (const renderer::PassTiming& pass : timings.passes) passTimes[pass.name].push_back(pass.gpuMs);
  }
  for (renderer::PassTiming& pass : order) pass.gpuMs = stereo::medianMs(passTimes[pass.name]).value_or(0.0);
  return {medianOf(totals), order};
}

namespace {
double processCpuMs() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  auto ms = [](const timeval& t) { return double(t.tv_sec) * 1e3 + double(t.tv_usec) * 1e-3; };
  return ms(usage.ru_utime) + ms(usage.ru_stime);
}
}  // namespace

double processCpuMsPerFrame(renderer::DeferredRenderer& deferred, const renderer::ViewMatrices& view, int repeat) {
  const double start = processCpuMs();
  for (int run = 0; run < repeat; ++run) (void)deferred.render(view);
  return (processCpuMs() - start) / double(std::max(repeat, 1));
}

std::vector<std::uint32_t> depthEdgeMask(const DepthImage& depth, double share) {
  const std::uint32_t w = depth.width, h = depth.height;
  auto logDepth = [&](std::uint32_t x, std::uint32_t y) {
    const float d = *depth.at(x, y);
    return std::isfinite(d) && d > 0.0f ? std::log(double(d)) : std::numeric_limits<double>::infinity();
  };
  std::vector<double> score(std::size_t(w) * h, 0.0);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      const double here = logDepth(x, y);
      double step = 0.0;
      auto compare = [&](std::uint32_t nx, std::uint32_t ny) {
        const double there = logDepth(nx, ny);
        if (std::isinf(here) != std::isinf(there)) step = std::numeric_limits<double>::max();
        else if (!std::isinf(here)) step = std::max(step, std::abs(there - here));
      };
      if (x > 0) compare(x - 1, y);
      if (x + 1 < w) compare(x + 1, y);
      if (y > 0) compare(x, y - 1);
      if (y + 1 < h) compare(x, y + 1);
      score[std::size_t(y) * w + x] = step;
    }
  auto hash = [](std::uint32_t i) {
    i ^= i >> 16;
    i *= 0x7feb352du;
    i ^= i >> 15;
    i *= 0x846ca68bu;
    return i ^ (i >> 16);
  };
  std::vector<std::uint32_t> order(score.size());
  std::iota(order.begin(), order.end(), 0u);
  const std::size_t count = std::min(order.size(), std::size_t(std::llround(share * double(order.size()))));
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(count), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return score[a] != score[b] ? score[a] > score[b] : hash(a) < hash(b);
  });
  std::vector<std::uint32_t> mask(score.size(), 0);
  for (std::size_t i = 0; i < count; ++i) mask[order[i]] = 1;
  return mask;
}

}  // namespace s3d::frame
