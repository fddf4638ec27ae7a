#pragma once
// An RGBA float image (interleaved, row-major, row 0 at the top of the data window) and its files.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

// Relative: this header is installed with the public API (include/phongcl/), beside its rooms.
#include "../exr/pixel_window.h"
#include "../gbuffer/gbuffer.h"  // image_like

namespace phongcl {

struct Image {
  int width = 0, height = 0;
  PixelWindow data_window, display_window;  // carried from the G-buffer so outputs line up with inputs
  std::vector<float> rgba;                  // 4 * width * height

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(4 * static_cast<std::size_t>(w) * h, 0.0f) {
    data_window = display_window = PixelWindow{0, 0, w - 1, h - 1};
  }
  std::size_t pixel_count() const { return static_cast<std::size_t>(width) * height; }
  float* pixel(std::size_t index) { return rgba.data() + 4 * index; }
  const float* pixel(std::size_t index) const { return rgba.data() + 4 * index; }
};

// An image with the same size and windows as the G-buffer it shades, all zero.
Image image_like(const GBuffer& gbuffer);

// Writes channels R G B A (float32 or half), same data/display window as the image; atomic.
void write_exr(const Image& image, const std::filesystem::path& file, ExrPixelType type = ExrPixelType::float32,
               ExrCompression compression = ExrCompression::zip);
// The same with the file first, as the public API (include/phongcl/phongcl.hpp) writes it.
inline void write_exr(const std::filesystem::path& file, const Image& image, ExrPixelType type = ExrPixelType::float32) {
  write_exr(image, file, type);
}
// One layer of a multilayer EXR: channels "<name>.R .G .B" (and ".A" with alpha), or plain
// "R G B A" for the unnamed layer compositors show by default.
struct ExrLayer {
  std::string name;
  const Image* image;
  bool with_alpha;
};
// Writes every layer into one EXR (float32 or half), atomically. The images must share size and
// windows (std::invalid_argument otherwise); the file takes the first one's windows.
void write_layered_exr(const std::vector<ExrLayer>& layers, const std::filesystem::path& file,
                       ExrPixelType type = ExrPixelType::float32, ExrCompression compression = ExrCompression::zip);
// Reads R G B (and A if present, else 1) from an EXR. Throws InputError on a bad file.
Image read_exr(const std::filesystem::path& file);

// Display encoding for looking at HDR values: scale by 2^exposure, tone map, sRGB-encode, 8 bits.
enum class ToneMap { clamp, reinhard, aces };
struct DisplaySettings {
  double exposure_stops = 0.0;
  ToneMap tone_map = ToneMap::reinhard;
};
// Exposure within +-40 stops (a factor of 1e12 either way): beyond it the 8-bit steps of the
// display curve fall outside float's range, and no image needs it.
inline constexpr double kMaxExposureStops = 40.0;
// Throws std::invalid_argument "exposure must be a finite number of stops in [-40, 40] (got nan)";
// every front end checks its exposure with it before shading.
void check_exposure(double stops);
// 8-bit sRGB RGBA of the whole image (image/display_encoder.h: of rows, for many frames). NaN
// displays as 0, +Inf as white.
std::vector<std::uint8_t> display_rgba8(const Image& image, const DisplaySettings& display);
// A PNG (tagged sRGB, fast zlib settings) of display_rgba8's bytes, in memory. Throws
// std::runtime_error with libpng's message when it refuses (e.g. an empty image).
std::string encode_png(const std::vector<std::uint8_t>& rgba, int width, int height);
// Writes display_rgba8 as a PNG, atomically.
void write_png(const Image& image, const std::filesystem::path& file, const DisplaySettings& display = {});
inline void write_png(const std::filesystem::path& file, const Image& image, const DisplaySettings& display = {}) {
  write_png(image, file, display);
}

// Per-pixel error of `test` against `expected` over the pixels where `mask` is true (all if empty),
// on the R, G, B channels. Relative error is |t - e| / max(|e|, abs_floor).
struct ErrorStats {
  std::size_t pixels_compared = 0;
  double max_abs = 0.0;
  double max_rel = 0.0;
  double rmse = 0.0;
  double psnr_db = 0.0;           // against peak = max |expected| (infinite when identical)
  std::size_t worst_pixel = 0;    // by relative error
  int worst_x = 0, worst_y = 0;
  int worst_channel = 0;
  double worst_test = 0.0, worst_expected = 0.0;
  std::size_t nonfinite_mismatches = 0;  // one is finite and the other is not, or NaN anywhere
  bool operator==(const ErrorStats&) const = default;
};
ErrorStats compare_images(const Image& test, const Image& expected, double abs_floor,
                          const std::vector<bool>& mask = {});

}  // namespace phongcl
