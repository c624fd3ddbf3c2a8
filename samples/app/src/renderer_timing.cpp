#include "renderer_timing.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

#include "bench_text.h"
#include "s3d/stereo/synthesis.h"

namespace s3d::app::detail {

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
  // clocks back up (an H100 timed a reference eye at 25.7 ms instead of 4.7 ms after 50 ms of warm-up).
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

std::vector<MaskedRenderRow> timeMaskedRenders(vk::Context& context, renderer::DeferredRenderer& deferred,
                                               const renderer::ViewMatrices& view, const std::string& scene, int repeat) {
  const DepthImage depth = deferred.readLinearDepth();
  std::vector<MaskedRenderRow> rows;
  for (double share : kMaskedRenderShares) {
    const std::vector<std::uint32_t> values = depthEdgeMask(depth, share);
    vk::Image mask = vk::createImage(context, VK_FORMAT_R32_UINT, deferred.width(), deferred.height(),
                                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    vk::uploadImage(context, mask, std::as_bytes(std::span(values)), vk::kComputeWrite);
    auto [frameMs, passes] = timeFrames(deferred, view, repeat, renderer::ShadeMask{&mask, 1});
    const double shaded = double(std::count(values.begin(), values.end(), 1u)) / double(values.size());
    rows.push_back({scene, share, shaded, frameMs, std::move(passes)});
  }
  return rows;
}

std::string maskedRenderMarkdown(const std::vector<MaskedRenderRow>& rows, int repeat) {
  std::ostringstream md;
  md << "Masked center frame (`DeferredRenderer::render` with a `ShadeMask` of the pixels with the largest depth "
        "steps, as the hybrid method picks them), GPU ms, median of "
     << repeat << " warm frames:\n\n";
  std::vector<std::string> names;
  for (const MaskedRenderRow& row : rows)
    for (const renderer::PassTiming& pass : row.passes)
      if (pass.name.rfind("shadow-", 0) != 0 && std::find(names.begin(), names.end(), pass.name) == names.end())
        names.push_back(pass.name);
  md << "| scene | mask share | frame | shadow maps |";
  for (const std::string& name : names) md << ' ' << name << " |";
  md << "\n|---|---|---|---|";
  for (std::size_t i = 0; i < names.size(); ++i) md << "---|";
  md << '\n';
  for (const MaskedRenderRow& row : rows) {
    double shadowMs = 0.0;
    for (const renderer::PassTiming& pass : row.passes)
      if (pass.name.rfind("shadow-", 0) == 0) shadowMs += pass.gpuMs;
    char share[32];
    std::snprintf(share, sizeof(share), "%g %%", std::round(row.shadedShare * 1000.0) / 10.0);
    md << "| " << row.scene << " | " << share << " | " << bench_text::msText(row.frameGpuMs) << " | " << bench_text::msText(shadowMs) << " |";
    for (const std::string& name : names) {
      auto pass = std::find_if(row.passes.begin(), row.passes.end(),
                               [&](const renderer::PassTiming& p) { return p.name == name; });
      md << ' ' << (pass == row.passes.end() ? std::string("-") : bench_text::msText(pass->gpuMs)) << " |";
    }
    md << '\n';
  }
  return md.str();
}

}  // namespace s3d::app::detail
