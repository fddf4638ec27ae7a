#include "cli/outputs.h"

#include <map>
#include <stdexcept>

namespace phongcl::cli {

namespace {
const std::map<std::string, ToneMap> kToneMaps{{"clamp", ToneMap::clamp}, {"reinhard", ToneMap::reinhard}, {"aces", ToneMap::aces}};
}

void ImageOutputs::add_options(CLI::App& command) {
  command.add_option("--out", exr_file, "Output EXR (R G B A)");
  command.add_flag("--half", half, "Write the EXR as half instead of float32");
  command.add_option("--png", png_file, "Also write an 8-bit sRGB PNG preview");
  command.add_option("--exposure", exposure, "PNG exposure in stops (default 0)");
  command.add_option("--tonemap", tone_map, "PNG tone map: clamp, reinhard or aces")
      ->check(CLI::IsMember({"clamp", "reinhard", "aces"}));
}

std::string ImageOutputs::write(const Image& image) const {
  if (exr_file.empty() && png_file.empty()) throw std::invalid_argument("nothing to write: give --out and/or --png");
  std::string written;
  if (!exr_file.empty()) {
    write_exr(image, exr_file, half ? ExrPixelType::half : ExrPixelType::float32);
    written = exr_file + (half ? " (half)" : " (float32)");
  }
  if (!png_file.empty()) {
    write_png(image, png_file, DisplaySettings{exposure, kToneMaps.at(tone_map)});
    written += (written.empty() ? "" : ", ") + png_file + " (sRGB, " + tone_map + ")";
  }
  return written;
}

}  // namespace phongcl::cli
