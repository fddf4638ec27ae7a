#pragma once
// What 8-bit outputs show: an image flattened over its background, scaled by an exposure, through
// a look and a display's view of an OpenColorIO config (color/color_config.h), then 8 bits. PNGs,
// sequences' PNGs and the server's PNG and JPEG frames all come from here.
//
// The processor is built as Blender builds its own (intern/opencolorio's display processor): the
// exposure scales the working space (scene_linear) values by 2^exposure, a look goes from there to
// its process space (OpenColorIO's LookTransform), and the display's view starts from wherever the
// look ended (a DisplayViewTransform with the view's own looks bypassed). With Blender's config, a
// PNG of an EXR is Blender's PNG of the same EXR (no dither) to 1/255 (docs/colour.md).
//
// Images are premultiplied RGBA (OpenEXR's convention): a pixel shows rgb + (1 - alpha) * background,
// and colour where alpha is 0 is not drawn (the shader leaves the scene's background colour there).
// NaN shows as 0; alpha is clamped to [0, 1] (NaN: 0). Installed with the public API.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "../image/image.h"
#include "color_config.h"

namespace phongcl {

class ByteSteps;
class ViewPipeline;

struct DisplaySettings {
  std::string display;                // empty: the config's default display
  std::string view;                   // empty: the display's default view
  std::string look;                   // empty or "None": no look
  double exposure_stops = 0.0;        // working-space values are scaled by 2^exposure first
  glm::dvec3 background{0.0};         // working space, shown where the image is transparent
};

class DisplayTransform {
 public:
  // InputError naming the config for a display, view or look it does not have (the message lists
  // those it has); std::invalid_argument for a non-finite exposure or background, or an exposure
  // beyond check_exposure's +-40 stops (image/image.h).
  DisplayTransform(const ColorConfig& config, const DisplaySettings& settings);

  // 8-bit RGBA (alpha 255: the background is flattened in) of rows [first_row, first_row + rows)
  // into out (4 bytes a pixel, indexed from the image's first pixel). Const: threads may encode
  // blocks of one image at once.
  void encode_rows(const Image& image, std::size_t first_row, std::size_t rows, std::uint8_t* out) const;
  // Every row, in blocks on every core.
  std::vector<std::uint8_t> encode(const Image& image) const;

  const std::string& display() const { return display_; }
  const std::string& view() const { return view_; }
  const std::string& look() const { return look_; }  // empty: none
  // How the processor runs: "compiled: per-channel table, 65^3 LUT (tetrahedral), ..." or
  // "OpenColorIO's CPU processor (why)".
  std::string pipeline() const;

 private:
  void encode_by_steps(const Image& image, std::size_t first, std::size_t end, std::uint8_t* out) const;

  std::string display_, view_, look_;
  std::shared_ptr<const ViewPipeline> pipeline_;
  // A view that is one monotone curve per channel: its bytes by the floats where they step up
  // (color/byte_steps.h), exposure folded in; empty otherwise.
  std::shared_ptr<const ByteSteps> steps_[3];
  float scale_;
  float background_[3];
};

// Writes the image's display encoding as an 8-bit PNG (tagged sRGB), atomically; InputError
// naming the file when it cannot.
void write_png(const Image& image, const std::filesystem::path& file, const DisplayTransform& display);
// The same through the config `ColorConfig::load()` finds ($OCIO, else the built-in one).
void write_png(const std::filesystem::path& file, const Image& image, const DisplaySettings& settings = {});

}  // namespace phongcl
