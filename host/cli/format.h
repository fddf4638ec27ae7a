#pragma once
// Human-readable numbers for summaries.
#include <cstddef>
#include <string>

namespace phongcl::cli {

std::string with_commas(std::size_t value);  // 1234567 -> "1,234,567"
std::string milliseconds(double ms);          // "3.42 ms"
std::string mpixels_per_second(std::size_t pixels, double ms);  // "54.8 Mpixels/s"

}  // namespace phongcl::cli
