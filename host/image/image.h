#pragma once
// An RGBA float image (interleaved, row-major, row 0 at the top of the data window) and its files.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
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

// What an image's EXR holds besides its pixels.
struct ExrWriteOptions {
  ExrPixelType type = ExrPixelType::float32;
  ExrCompression compression = ExrCompression::zip;
  // Images are premultiplied RGBA, as OpenEXR's convention has it: colour where alpha is 0 is light
  // that a compositor's `over` adds to the plate. false: RGB 0 there (the shader's background
  // colour is for previews, color/display.h); true: as the image holds it.
  bool keep_color_where_transparent = false;
  std::optional<Chromaticities> chromaticities{};  // the RGB primaries, as OpenEXR's standard attribute
};

// Writes channels R G B A, same data/display window as the image; atomic.
void write_exr(const Image& image, const std::filesystem::path& file, const ExrWriteOptions& options = {});
// The bytes write_exr writes, made in memory (an HTTP response's body).
std::string encode_exr(const Image& image, const ExrWriteOptions& options = {});
// The same with the file first, as the public API (include/phongcl/phongcl.hpp) writes it.
inline void write_exr(const std::filesystem::path& file, const Image& image, ExrPixelType type = ExrPixelType::float32) {
  write_exr(image, file, ExrWriteOptions{.type = type});
}
// One layer of a multilayer EXR: channels "<name>.R .G .B" (and ".A" with alpha), or plain
// "R G B A" for the unnamed layer compositors show by default.
struct ExrLayer {
  std::string name;
  const Image* image;
  bool with_alpha;
};
// Writes every layer into one EXR, atomically. The images must share size and windows
// (std::invalid_argument otherwise); the file takes the first one's windows. Each layer's RGB is 0
// where its image's alpha is 0 unless the options keep it (with_alpha only says whether A is written).
void write_layered_exr(const std::vector<ExrLayer>& layers, const std::filesystem::path& file,
                       const ExrWriteOptions& options = {});
// Reads R G B (and A if present, else 1) from an EXR, or <layer>.R, .G, .B (.A) of a multilayer one
// (a render's "ViewLayer.Combined"). Throws InputError on a bad file or a missing channel.
Image read_exr(const std::filesystem::path& file, const std::string& layer = "");

// Exposure within +-40 stops (a factor of 1e12 either way): beyond it the 8-bit steps of a
// display curve fall outside float's range, and no image needs it.
inline constexpr double kMaxExposureStops = 40.0;
// Throws std::invalid_argument "exposure must be a finite number of stops in [-40, 40] (got nan)";
// every front end checks its exposure with it before shading.
void check_exposure(double stops);
// A PNG (tagged sRGB, fast zlib settings) of 8-bit RGBA bytes (a display transform's,
// color/display.h), in memory. Throws std::runtime_error with libpng's message when it refuses
// (e.g. an empty image).
std::string encode_png(const std::vector<std::uint8_t>& rgba, int width, int height);

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
