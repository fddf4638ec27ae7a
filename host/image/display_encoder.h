#pragma once
// display_rgba8 with its settings resolved once, for encoding many frames fast: exposure, tone
// curve and sRGB are one monotonic function of the input value, so the 255 input values where the
// output byte steps up (found by bisection on the exact function) turn each channel into a table
// lookup and a comparison, with the same bytes as the formula.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "image/image.h"

namespace phongcl {

class DisplayEncoder {
 public:
  explicit DisplayEncoder(const DisplaySettings& display);
  // 8-bit sRGB RGBA of rows [first_row, first_row + rows) into out (4 bytes a pixel, indexed from
  // the image's first pixel). Const: threads may encode blocks of one image at once.
  void encode_rows(const Image& image, std::size_t first_row, std::size_t rows, std::uint8_t* out) const;

 private:
  // Positive floats order as their bit patterns do: steps_[k] is the pattern of the first value
  // whose byte exceeds k (none for 255), coarse_[p >> 16] the byte at the start of each bucket of
  // patterns.
  std::array<std::uint32_t, 256> steps_{};
  std::vector<std::uint8_t> coarse_;
};

}  // namespace phongcl
