#pragma once
// File names of a frame sequence: "shot.####.exr" (the frame padded to as many digits as there are
// #) or printf's "shot.%04d.exr" / "shot.%d.exr". A name with neither is one file for every frame.
#include <filesystem>
#include <string>
#include <vector>

namespace phongcl {

class FramePattern {
 public:
  FramePattern() = default;
  // Throws std::invalid_argument on two placeholders or a malformed %...d.
  explicit FramePattern(std::string text);

  bool is_pattern() const { return width_ >= 0; }
  const std::string& text() const { return text_; }
  // The file of `frame` (the text itself when it is not a pattern). Negative frames get a '-' before
  // the padded digits, as printf writes them.
  std::filesystem::path path(int frame) const;
  // The frames whose files exist in the pattern's directory, ascending.
  std::vector<int> frames_on_disk() const;

 private:
  std::string text_, prefix_, suffix_;
  int width_ = -1;  // digits to pad to; -1: not a pattern
};

}  // namespace phongcl
