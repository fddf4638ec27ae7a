#pragma once
// A G-buffer in memory: structure of arrays, one float per pixel per channel, row-major,
// row 0 at the top of the data window. The file: docs/formats.md "G-buffer (OpenEXR)".
#include <array>
#include <cstddef>
#include <filesystem>
#include <vector>

// Relative: this header is installed with the public API (include/phongcl/), beside its room.
#include "../exr/pixel_window.h"

namespace phongcl {

using Plane = std::vector<float>;          // one channel, width*height values
using Planes3 = std::array<Plane, 3>;      // x,y,z or r,g,b

struct GBuffer {
  int width = 0, height = 0;           // of the data window
  PixelWindow data_window, display_window;
  Planes3 position;                    // P.X P.Y P.Z
  Planes3 normal;                      // N.X N.Y N.Z, any length
  Plane material;                      // index into the scene's materials; negative = background
  // Optional per-pixel material channels; an empty group means "use the material table".
  Planes3 ka, kd, ks;
  Plane shininess;
  // Optional: the fraction of each pixel the surface covers, in [0, 1] (anti-aliased edges of
  // renderers' files). Shaded pixels then output colour * coverage with alpha = coverage
  // (premultiplied); empty means 1 everywhere.
  Plane coverage;
  // Optional: the renderer's own image of the frame (linear RGB as the file stores it, e.g.
  // Blender's Combined), to compare the relit image with. Shading never reads it; empty if absent.
  Planes3 beauty;
  std::filesystem::path source;        // for messages
  ExrCompression compression = ExrCompression::zip;  // the file's (outputs default to the input's)

  std::size_t pixel_count() const { return static_cast<std::size_t>(width) * height; }
  bool has_per_pixel_ka() const { return !ka[0].empty(); }
  bool has_per_pixel_kd() const { return !kd[0].empty(); }
  bool has_per_pixel_ks() const { return !ks[0].empty(); }
  bool has_per_pixel_shininess() const { return !shininess.empty(); }
  bool has_coverage() const { return !coverage.empty(); }
  bool has_beauty() const { return !beauty[0].empty(); }
};

// Why a pixel is or is not shaded. The kernel's packing and the reference both use this, so the
// two agree on which pixels are background by construction.
enum class PixelClass {
  shaded,
  background,            // material < 0
  nonfinite_position,    // NaN/Inf in P
  nonfinite_normal,      // NaN/Inf in N
  nonfinite_material,    // NaN/Inf in material or any per-pixel material channel
};
PixelClass classify_pixel(const GBuffer& gbuffer, std::size_t index);
// classify_pixel for pixels [first, first + count) into classes[0, count), fast where, as usual,
// nearly every pixel is shaded.
void classify_pixels(const GBuffer& gbuffer, std::size_t first, std::size_t count, PixelClass* classes);

// Throws InputError (naming gbuffer.source and the first offending pixel) if a shaded pixel's
// material index is not an integer in [0, material_count) or a per-pixel shininess is negative.
void check_materials(const GBuffer& gbuffer, std::size_t material_count);

// Reads a G-buffer EXR in any layout, detected from its channels (the same as
// read_gbuffer(file, ReadOptions{}) of gbuffer/layouts.h, which also says what it found): single-
// or multi-part, scanline or tiled, half, float or uint, any compression. Throws InputError on a
// missing required channel, a truncated or corrupt file, or an unreadable one.
GBuffer read_gbuffer(const std::filesystem::path& file);

// Writes `gbuffer` in the phongcl layout, atomically (temp file, then rename).
void write_gbuffer(const GBuffer& gbuffer, const std::filesystem::path& file,
                   ExrPixelType type = ExrPixelType::float32, ExrCompression compression = ExrCompression::zip);

}  // namespace phongcl
