#include "capi_checks.h"

#include <cmath>
#include <stdexcept>

#include "s3d/number_text.h"

namespace s3d::capi {

std::string Name::text() const {
  std::string result = base;
  if (index >= 0) result.append("[").append(std::to_string(index)).append("]");
  if (field) result.append(".").append(field);
  return result;
}

void fail(const std::string& message) { throw std::invalid_argument(message); }

void requireNotNull(const void* pointer, Name name) {
  if (!pointer) fail(name.text() + " is NULL");
}

void failNullHandle(Name name) { fail(name.text() + " is VK_NULL_HANDLE"); }

void requireFinite(float value, Name name) {
  if (!std::isfinite(value)) fail(name.text() + " must be finite (got " + numberText(value) + ")");
}

void requirePositive(float value, Name name) {
  if (!(value > 0.0f) || !std::isfinite(value))
    fail(name.text() + " must be positive and finite (got " + numberText(value) + ")");
}

void requireNonNegative(float value, Name name) {
  if (!(value >= 0.0f) || !std::isfinite(value))
    fail(name.text() + " must be >= 0 and finite (got " + numberText(value) + ")");
}

void requireRange(float value, float low, float high, Name name) {
  if (!(value >= low && value <= high))  // NaN fails too; infinities fall outside any finite range
    fail(name.text() + " " + numberText(value) + " is outside [" + numberText(low) + ", " + numberText(high) + "]");
}

void requireEnum(std::int64_t value, std::int64_t first, std::int64_t last, Name name) {
  if (value < first || value > last)
    fail(name.text() + " " + std::to_string(value) + " is not one of its enum's values (" + std::to_string(first) +
         " .. " + std::to_string(last) + ")");
}

void requireImageSize(std::uint32_t value, std::uint32_t limit, Name name, std::uint32_t factor, const char* why) {
  if (value == 0) fail(name.text() + " is 0");
  const std::uint64_t size = std::uint64_t(value) * factor;
  if (size <= limit) return;
  const std::string derived =
      factor == 1 ? std::string() : " (x" + std::to_string(factor) + " for " + why + ": " + std::to_string(size) + ")";
  fail(name.text() + " " + std::to_string(value) + derived + " exceeds the device's maxImageDimension2D " +
       std::to_string(limit));
}

}  // namespace s3d::capi
