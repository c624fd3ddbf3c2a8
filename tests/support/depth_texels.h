#pragma once
// A device depth as a depth buffer of a given format stores it: shared by the host-pass tests and the host
// benchmark, so both hand the pass the same texels.
#include <vulkan/vulkan.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace s3d::test {

template <typename Value>
void appendBytes(std::vector<std::byte>& bytes, const Value& value) {
  const auto* first = reinterpret_cast<const std::byte*>(&value);
  bytes.insert(bytes.end(), first, first + sizeof(value));
}

// Appends `deviceDepth` (0..1) as `format` stores it: D16, D24S8 (24 bits, stencil 0) or a 32-bit float (D32).
// Returns the depth the buffer then holds, quantized for D16 and D24S8.
inline float appendDepthTexel(std::vector<std::byte>& bytes, VkFormat format, float deviceDepth) {
  if (format == VK_FORMAT_D16_UNORM) {
    const auto q = std::uint16_t(std::lround(deviceDepth * 65535.0f));
    appendBytes(bytes, q);
    return float(q) / 65535.0f;
  }
  if (format == VK_FORMAT_D24_UNORM_S8_UINT) {
    const auto q = std::uint32_t(std::lround(double(deviceDepth) * 16777215.0));
    appendBytes(bytes, q);
    return float(double(q) / 16777215.0);
  }
  appendBytes(bytes, deviceDepth);
  return deviceDepth;
}

}  // namespace s3d::test
