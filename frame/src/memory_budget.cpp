#include "s3d/frame/memory_budget.h"

#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "s3d/stereo/disparity_map_shared.h"

namespace s3d::frame {
namespace {

// Host bytes per output pixel of a render job, counted from the images it holds at its peak (step 7, the
// writes): center color 4 + weapon mask 1 + eyes 8 + HDR eyes 32 + depth 4 + HDR center 16; two reference eyes
// at 4 + 4 + 16 + 1; region masks 3; SSIM's per-pixel sums 16; HUD copies of center, eyes and references 20;
// anaglyph 4, side-by-side and top-bottom up to 8 each, heat maps 8, PNG encoding 4, EXR half copy and its
// encoded stream 32.
constexpr std::uint64_t kRenderHostBytesPerOutputPixel = 65 + 50 + 3 + 16 + 20 + 64;
// And per rendered pixel (the guard band's width): depth 4, HDR 16, eyes 8, HDR eyes 32, and one read-back at a
// time (half-float bytes and their float copy) 24.
constexpr std::uint64_t kRenderHostBytesPerRenderedPixel = 84;
// The hybrid method per rendered pixel: device: the eye renderer's G-buffer per sample and its resolved images,
// score bins and masks 16, the displaced eyes 8; host: masks 2, rendered HDR eyes 32.
// Each eye renderer's ray-cast screen bins: two layers' count and S3D_RAYCAST_BIN_CAPACITY (64) entries of 4 bytes
// per 16x16 pixels, 2.03 bytes, rounded up.
constexpr std::uint64_t kRaycastBinBytesPerRenderedPixel = 3;
constexpr std::uint64_t kHybridDeviceBytesPerRenderedPixel =
    kDeviceBytesPerRenderedPixel + 16 + 8 + kRaycastBinBytesPerRenderedPixel;
constexpr std::uint64_t kHybridHostBytesPerRenderedPixel = 2 + 32;
// And per row: the classification's row histograms (2 x 256 bins) and the threshold's split offsets (2).
constexpr std::uint64_t kHybridDeviceBytesPerRow = 4 * (2 * 256 + 2);
// And once: the second renderer's pipelines and shadow atlases (lavapipe: 19-31 MB more peak resident memory
// than the search method at 1280x720 and 320x180).
constexpr std::uint64_t kHybridFixedBytes = 48ull << 20;
// A nonlinear map's per-layer reference, per rendered pixel: each layer's display 4, depth 4, HDR 16, transparent,
// cut-out and first-person masks 3 held at once for one eye, and the composite 27; the mapped depths (the stereo
// pass's copy, its output crop and two mapped reference depths) 16.
constexpr std::uint64_t kReferenceLayerHostBytesPerRenderedPixel = 27;
constexpr std::uint64_t kMappedDepthHostBytesPerRenderedPixel = 16;

// `s3d convert` per pixel: host: color 4 (an EXR's float color and file bytes 32 more), depth 4 (its file's
// values 4), eyes 8, anaglyph 4, side-by-side 8, top-bottom 8, two references 8, PNG encoding 4, read-back 8;
// device: color 4, depth 4, eyes 8, the forward method's two pairs of per-eye z-buffers 16, staging 16.
constexpr std::uint64_t kConvertHostBytesPerPixel = 4 + 32 + 4 + 4 + 8 + 4 + 8 + 8 + 8 + 4 + 8;
constexpr std::uint64_t kConvertDeviceBytesPerPixel = 4 + 4 + 8 + 16 + 16;

std::uint64_t readMemAvailable() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return 0;
}

std::optional<std::uint64_t> readNumberFile(const char* path) {
  std::ifstream file(path);
  std::string text;
  if (!(file >> text) || text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) return std::nullopt;
  try {
    return std::stoull(text);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

[[noreturn]] void failEstimate(const MemoryEstimate& estimate, std::uint64_t needed, const std::string& kind,
                               std::uint64_t limit, const std::string& source) {
  std::string message = estimate.what + " needs an estimated " + byteText(needed) + " of " + kind + ", more than the " +
                        byteText(limit) + " " + source;
  if (!estimate.lower.empty()) message += "; lower " + estimate.lower;
  throw std::invalid_argument(message);
}

}  // namespace

MemoryEstimate renderMemoryEstimate(std::uint32_t width, std::uint32_t height, std::uint32_t renderedWidth,
                                    std::uint32_t supersample, bool hybridEyes, std::uint32_t referenceLayers) {
  const std::uint64_t outputPixels = std::uint64_t(width) * height;
  const std::uint64_t renderedPixels = std::uint64_t(std::max(renderedWidth, width)) * height;
  const std::uint64_t samples = std::uint64_t(supersample) * supersample;
  MemoryEstimate estimate;
  estimate.hostBytes = kRunFixedBytes + kRenderHostBytesPerOutputPixel * outputPixels +
                       kRenderHostBytesPerRenderedPixel * renderedPixels;
  estimate.deviceBytes = (kDeviceBytesPerSample * samples + kDeviceBytesPerRenderedPixel) * renderedPixels;
  if (hybridEyes) {
    estimate.hostBytes += kHybridFixedBytes + kHybridHostBytesPerRenderedPixel * renderedPixels;
    estimate.deviceBytes += (kDeviceBytesPerSample * samples + kHybridDeviceBytesPerRenderedPixel) * renderedPixels +
                            kHybridDeviceBytesPerRow * height;
    estimate.concurrentDeviceBytes =
        (kDeviceBytesPerSample * samples + kDeviceBytesPerRenderedPixel + kRaycastBinBytesPerRenderedPixel) *
        renderedPixels;
  }
  if (referenceLayers > 1)
    estimate.hostBytes += (kReferenceLayerHostBytesPerRenderedPixel * (referenceLayers + 1) +
                           kMappedDepthHostBytesPerRenderedPixel) * renderedPixels;
  estimate.what = std::to_string(width) + "x" + std::to_string(height);
  if (referenceLayers > 1) estimate.what += ", up to " + std::to_string(referenceLayers) + " reference layers";
  if (supersample > 1) estimate.what += ", supersample " + std::to_string(supersample);
  if (renderedWidth > width)
    estimate.what += ", guard band 2 x " + std::to_string((renderedWidth - width) / 2) + " columns";
  estimate.what += hybridEyes ? " (center view, eyes, the hybrid's eye renders and reference eyes)"
                              : " (center view, eyes and reference eyes)";
  estimate.lower = "--resolution or --supersample";
  return estimate;
}

std::uint32_t maxReferenceLayers(stereo::DisparityMapping mapping) {
  return mapping == stereo::DisparityMapping::Nonlinear ? S3D_DISPARITY_MAP_KNOTS - 1 : 1;
}

MemoryEstimate convertMemoryEstimate(std::uint32_t width, std::uint32_t height) {
  const std::uint64_t pixels = std::uint64_t(width) * height;
  MemoryEstimate estimate;
  estimate.hostBytes = kRunFixedBytes + kConvertHostBytesPerPixel * pixels;
  estimate.deviceBytes = kConvertDeviceBytesPerPixel * pixels;
  estimate.what = std::to_string(width) + "x" + std::to_string(height);
  return estimate;
}

MemoryLimit hostMemoryLimit(std::optional<std::uint64_t> userLimit) {
  MemoryLimit limit{readMemAvailable(), "available"};
  if (limit.bytes == 0) limit = {std::numeric_limits<std::uint64_t>::max(), "available"};
  // cgroup v2: the container's own ceiling, often far below the machine's.
  if (const auto max = readNumberFile("/sys/fs/cgroup/memory.max")) {
    const std::uint64_t current = readNumberFile("/sys/fs/cgroup/memory.current").value_or(0);
    const std::uint64_t headroom = *max > current ? *max - current : 0;
    if (headroom < limit.bytes) limit = {headroom, "left under the cgroup's memory.max"};
  }
  rlimit addressSpace{};
  if (::getrlimit(RLIMIT_AS, &addressSpace) == 0 && addressSpace.rlim_cur != RLIM_INFINITY &&
      std::uint64_t(addressSpace.rlim_cur) < limit.bytes)
    limit = {std::uint64_t(addressSpace.rlim_cur), "allowed by the address-space limit (ulimit -v)"};
  if (userLimit && *userLimit < limit.bytes) limit = {*userLimit, "allowed by --memory-limit"};
  return limit;
}

void requireHostMemory(const MemoryEstimate& estimate, std::optional<std::uint64_t> userLimit, bool deviceIsHost) {
  const MemoryLimit limit = hostMemoryLimit(userLimit);
  const std::uint64_t needed = deviceIsHost ? estimate.totalBytes() : estimate.hostBytes;
  if (needed > limit.bytes) failEstimate(estimate, needed, "memory", limit.bytes, limit.source);
}

void requireMemory(const vk::Context& context, const MemoryEstimate& estimate, std::optional<std::uint64_t> userLimit) {
  if (context.isCpuDevice()) {
    requireHostMemory(estimate, userLimit, true);
    return;
  }
  requireHostMemory(estimate, userLimit, false);
  VkPhysicalDeviceMemoryProperties properties{};
  vkGetPhysicalDeviceMemoryProperties(context.physicalDevice(), &properties);
  std::uint64_t largest = 0;
  for (std::uint32_t i = 0; i < properties.memoryHeapCount; ++i)
    if (properties.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      largest = std::max<std::uint64_t>(largest, properties.memoryHeaps[i].size);
  const std::uint64_t deviceBytes = estimate.deviceBytes + (context.hasConcurrentQueue() ? estimate.concurrentDeviceBytes : 0);
  if (largest > 0 && deviceBytes > largest)
    failEstimate(estimate, deviceBytes, "GPU memory", largest, "of " + context.deviceName());
}

std::uint64_t peakResidentBytes() {
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return std::uint64_t(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

std::string byteText(std::uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  double value = double(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 4) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  if (unit == 0)
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(text, sizeof text, value < 10.0 ? "%.1f %s" : "%.0f %s", value, units[unit]);
  return text;
}

std::optional<std::uint64_t> parseByteSize(const std::string& text) {
  std::size_t end = 0;
  while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) || text[end] == '.')) ++end;
  if (end == 0) return std::nullopt;
  double value = 0.0;
  std::istringstream number(text.substr(0, end));
  if (!(number >> value) || !number.eof()) return std::nullopt;
  std::string unit = text.substr(end);
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  if (unit.size() >= 3 && unit.compare(unit.size() - 2, 2, "IB") == 0) unit.resize(unit.size() - 2);
  else if (unit.size() == 2 && unit.back() == 'B') unit.pop_back();
  double scale = 1.0;
  if (unit.empty() || unit == "B") scale = 1.0;
  else if (unit == "K") scale = 0x1p10;
  else if (unit == "M") scale = 0x1p20;
  else if (unit == "G") scale = 0x1p30;
  else if (unit == "T") scale = 0x1p40;
  else return std::nullopt;
  const double bytes = std::floor(value * scale);
  if (!(bytes >= 1.0) || bytes > 0x1p60) return std::nullopt;
  return std::uint64_t(bytes);
}

}  // namespace s3d::frame
