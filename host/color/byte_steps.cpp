#include "color/byte_steps.h"

#include <limits>

namespace phongcl {

std::optional<ByteSteps> ByteSteps::make(const std::function<std::uint8_t(float)>& byte_of) {
  ByteSteps steps;
  const auto byte_at = [&](std::uint32_t bits) { return byte_of(std::bit_cast<float>(bits)); };
  const int lowest = byte_at(0), highest = byte_at(kInfinityBits);
  for (int k = 0; k < 256; ++k) {
    if (k < lowest) continue;  // every value's byte exceeds k: step at 0
    if (k >= highest) {
      steps.steps_[k] = std::numeric_limits<std::uint32_t>::max();  // no value's byte exceeds k
      continue;
    }
    std::uint32_t below = 0, above = kInfinityBits;  // byte(below) <= k < byte(above)
    while (above - below > 1) {
      const std::uint32_t middle = below + (above - below) / 2;
      (byte_at(middle) > k ? above : below) = middle;
    }
    steps.steps_[k] = above;
  }
  for (int k = lowest; k + 1 < highest; ++k)
    if (steps.steps_[k] >> kCoarseShift == steps.steps_[k + 1] >> kCoarseShift) return std::nullopt;
  int byte = lowest;
  for (std::size_t bucket = 0; bucket < steps.coarse_.size(); ++bucket) {
    while (byte < highest && steps.steps_[byte] <= (bucket << kCoarseShift)) ++byte;
    steps.coarse_[bucket] = static_cast<std::uint8_t>(byte);
  }
  return steps;
}

}  // namespace phongcl
