#pragma once
// What EXR files say about pixels that G-buffers and images share: windows, the stored type and
// the compression.

namespace phongcl {

// Inclusive pixel bounds, as OpenEXR states data and display windows.
struct PixelWindow {
  int x_min = 0, y_min = 0, x_max = -1, y_max = -1;
  int width() const { return x_max - x_min + 1; }
  int height() const { return y_max - y_min + 1; }
  bool operator==(const PixelWindow&) const = default;
};

// How channels are stored in a written EXR.
enum class ExrPixelType { half, float32 };

// OpenEXR's compression methods, in its own order (exr/exr_channels.h converts and names them).
enum class ExrCompression { none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab };

}  // namespace phongcl
