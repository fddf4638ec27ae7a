#include "cli/format.h"

#include <cstdio>

namespace phongcl::cli {

std::string with_commas(std::size_t value) {
  const std::string digits = std::to_string(value);
  std::string grouped;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped += ',';
    grouped += digits[i];
  }
  return grouped;
}

std::string milliseconds(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, ms < 10 ? "%.2f ms" : "%.1f ms", ms);
  return text;
}

std::string mpixels_per_second(std::size_t pixels, double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f Mpixels/s", ms > 0 ? static_cast<double>(pixels) / (ms * 1e3) : 0.0);
  return text;
}

}  // namespace phongcl::cli
