#pragma once
// Numbers in messages as users wrote them: the shortest text that reads back as the same value ("0.02",
// "1e-07", "-1"), where std::to_string prints every float with six decimals ("0.020000", tiny values as
// "0.000000").
#include <charconv>
#include <string>

namespace s3d {

template <typename T>
std::string numberText(T value) {
  char text[32];
  const auto [end, error] = std::to_chars(text, text + sizeof(text), value);
  return error == std::errc() ? std::string(text, end) : std::string("?");
}

}  // namespace s3d
