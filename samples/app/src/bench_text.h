#pragma once
// How `s3d bench` writes its numbers into Markdown and SVG (bench_markdown.cpp, bench_targets.cpp, bench_hybrid.cpp,
// bench_plot.cpp and the other bench_*.cpp).
#include <cstdio>
#include <optional>
#include <string>

#include "s3d/app/report_json.h"

namespace s3d::app::bench_text {

inline std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), pattern, value);
  return text;
}

inline std::string percentText(double fraction) { return format("%g", double(tidy(float(fraction * 100.0)))); }

inline std::string msText(const std::optional<double>& ms) {
  if (!ms) return "n/a";
  return *ms >= 10.0 ? format("%.1f", *ms) : *ms >= 1.0 ? format("%.2f", *ms) : format("%.3f", *ms);
}

inline std::optional<double> ratio(const std::optional<double>& numerator, const std::optional<double>& denominator) {
  if (!numerator || !denominator || !(*denominator > 0.0)) return std::nullopt;
  return *numerator / *denominator;
}

inline std::string ratioText(const std::optional<double>& value) {
  if (!value) return "n/a";
  return *value > 0.0 && *value < 1.0 ? format("%.3f", *value) + " (1/" + format("%.0f", 1.0 / *value) + ")"
                                      : format("%.2f", *value);
}

inline std::string dbPair(double left, double right) { return format("%.2f", left) + " / " + format("%.2f", right); }

inline std::string xmlEscaped(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

}  // namespace s3d::app::bench_text
