#include "cli/format.h"

#include <cstdio>

namespace phongcl::cli {

std::string with_commas(std::size_t value) {
  std::string digits = std::to_string(value);
  for (int at = static_cast<int>(digits.size()) - 3; at > 0; at -= 3) digits.insert(static_cast<std::size_t>(at), ",");
  return digits;
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
