#pragma once
// Every tool run's memory, estimated from its image sizes before anything is allocated and checked against
// what the machine has: a too-large resolution ends at once with one error naming the estimate and the limit,
// instead of growing past the machine's memory minutes later.
#include <cstdint>
#include <optional>
#include <string>

#include "s3d/stereo/stereo.h"
#include "s3d/vk/context.h"

namespace s3d::frame {

struct MemoryEstimate {
  std::uint64_t hostBytes = 0;    // images in main memory: read back, compared, packed and encoded
  std::uint64_t deviceBytes = 0;  // GPU images: render targets at N x N samples, eyes, staging
  // GPU images added on a device with a second queue (vk::Context::hasConcurrentQueue): the hybrid's second eye
  // renderer, which renders the right eye while the first renders the left (requireMemory counts them there).
  std::uint64_t concurrentDeviceBytes = 0;
  std::string what;               // what was counted, e.g. "1920x1080, supersample 2, guard band 2 x 40 columns"
  std::string lower;              // the options that lower it, e.g. "--resolution or --supersample"
  std::uint64_t totalBytes() const { return hostBytes + deviceBytes; }
};

// The renderer's and the stereo pass's bytes, and the fixed cost of a run, as counted from their formats (see
// memory_budget.cpp) and checked against the peak resident memory on lavapipe (docs/RESULTS.md).
inline constexpr std::uint64_t kRunFixedBytes = 128ull << 20;  // Vulkan driver, shaders, shadow maps, Embree, scene
inline constexpr std::uint64_t kDeviceBytesPerSample = 42;     // per sample: the renderer's targets (38, DESIGN.md) and 4 to spare
inline constexpr std::uint64_t kDeviceBytesPerRenderedPixel = 40;  // resolved display/depth/HDR, both eyes, readback staging

// One `s3d render` frame (also a --sequence frame, a bench scene, a regress case, the tune view): the center
// view and the reference eyes at renderedWidth x height with supersample^2 samples, and every output-size image
// the job keeps at once (eyes and references in 8-bit and HDR, depth, masks, HUD copies, packed outputs, PNG
// and EXR encoding). hybridEyes: the hybrid method's eye renderer (and a second one's device bytes where the eyes
// render at once), its classification and masks on the device and the masks and rendered HDR eyes read back.
// referenceLayers: the renderings per reference eye (a nonlinear map's per-layer reference, layered_reference.h:
// all layers of an eye held at once, and the mapped depths); 1 for the linear mapping.
MemoryEstimate renderMemoryEstimate(std::uint32_t width, std::uint32_t height, std::uint32_t renderedWidth,
                                    std::uint32_t supersample, bool hybridEyes = false,
                                    std::uint32_t referenceLayers = 1);

// The most renderings per reference eye a mapping can take (the nonlinear map's segments).
std::uint32_t maxReferenceLayers(stereo::DisparityMapping mapping);

// `s3d convert` of one width x height frame (inputs decoded, eyes, packed outputs, GPU copies).
MemoryEstimate convertMemoryEstimate(std::uint32_t width, std::uint32_t height);

// The memory a run may use: the smaller of what the kernel reports available (MemAvailable), the cgroup's
// headroom (memory.max - memory.current) and `userLimit` (--memory-limit), and where that figure came from.
struct MemoryLimit {
  std::uint64_t bytes = 0;
  std::string source;  // "available memory", "the cgroup's memory.max", "--memory-limit"
};
MemoryLimit hostMemoryLimit(std::optional<std::uint64_t> userLimit);

// Before any Vulkan start-up: throws std::invalid_argument naming the estimate, the limit and estimate.lower when
// the host part (and the device part too when deviceIsHost, e.g. --device cpu) exceeds the host limit.
void requireHostMemory(const MemoryEstimate& estimate, std::optional<std::uint64_t> userLimit, bool deviceIsHost);

// After the context exists, before the job allocates: on a CPU device (lavapipe) host and device images share
// main memory; on a GPU the device part must fit its largest device-local heap.
void requireMemory(const vk::Context& context, const MemoryEstimate& estimate, std::optional<std::uint64_t> userLimit);

// The process's peak resident memory so far (getrusage), for report.json next to the estimate.
std::uint64_t peakResidentBytes();

// "1.5 GiB", "640 MiB", "12 KiB", "100 bytes".
std::string byteText(std::uint64_t bytes);
// "2GiB", "1.5G", "512MiB", "800M", "65536": binary multiples (K, M, G, T, with or without "iB"/"B"). Empty on
// anything else, zero or beyond 2^60.
std::optional<std::uint64_t> parseByteSize(const std::string& text);

}  // namespace s3d::frame
