#pragma once
// The C API's argument checks: each failure throws std::invalid_argument naming the parameter or field as the C
// caller spells it (s3d.h), never a C++ name. Names are rendered only on failure, so checks allocate nothing.
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <string>

#include <vulkan/vulkan.h>

#include "s3d/s3d.h"

namespace s3d::capi {

// "base", "base.field", "base[index]" or "base[index].field".
struct Name {
  const char* base;
  const char* field = nullptr;
  std::int64_t index = -1;
  std::string text() const;
  Name operator/(const char* member) const { return {base, member, index}; }
};

[[noreturn]] void fail(const std::string& message);

void requireNotNull(const void* pointer, Name name);
void failNullHandle(Name name);
template <typename Handle>  // any Vulkan handle, dispatchable (a pointer) or not (a pointer or a 64-bit integer)
void requireHandle(Handle handle, Name name) {
  if (!handle) failNullHandle(name);
}
void requireFinite(float value, Name name);
void requirePositive(float value, Name name);     // finite and > 0
void requireNonNegative(float value, Name name);  // finite and >= 0
void requireRange(float value, float low, float high, Name name);  // finite and in [low, high]
void requireEnum(std::int64_t value, std::int64_t first, std::int64_t last, Name name);
// A C enum field as the caller stored it: C lets any int sit in an enum, and loading one outside the enum's values
// as the enum type is undefined behaviour in C++, so a field is read as its bytes until it has been checked.
template <typename Enum>
std::int64_t rawEnum(const Enum& field) {
  std::underlying_type_t<Enum> value;
  std::memcpy(&value, &field, sizeof value);
  return std::int64_t(value);
}
// value * factor in 1 ..= limit; `why` names what multiplies the field ("S3D_OUTPUT_SIDE_BY_SIDE_FULL").
void requireImageSize(std::uint32_t value, std::uint32_t limit, Name name, std::uint32_t factor = 1,
                      const char* why = nullptr);

}  // namespace s3d::capi
