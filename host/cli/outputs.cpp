#include "cli/outputs.h"

#include <map>
#include <stdexcept>

namespace phongcl::cli {

namespace {
const std::map<std::string, ToneMap> kToneMaps{{"clamp", ToneMap::clamp}, {"reinhard", ToneMap::reinhard}, {"aces", ToneMap::aces}};

std::string pixel_type_name(bool half) { return half ? " (half)" : " (float32)"; }
}  // namespace

void ImageOutputs::add_options(CLI::App& command) {
  command.add_option("--out", exr_file, "Output EXR (R G B A)");
  command.add_flag("--half", half, "Write EXRs as half instead of float32");
  command.add_option("--png", png_file, "Also write an 8-bit sRGB PNG preview");
  command.add_option("--exposure", exposure, "PNG exposure in stops: values are scaled by 2^exposure (default 0)");
  command.add_option("--tonemap", tone_map,
                     "PNG tone map: clamp, reinhard (x/(1+x), default) or aces (Narkowicz's fit of the ACES filmic curve)")
      ->check(CLI::IsMember({"clamp", "reinhard", "aces"}));
}

void ImageOutputs::add_aov_option(CLI::App& command) {
  command.add_option("--aov", aov_file,
                     "Also write a multilayer EXR: ambient.RGB, diffuse.RGB, specular.RGB and the combined R G B A");
}

std::string ImageOutputs::write(const Image& image) const {
  if (exr_file.empty() && png_file.empty()) throw std::invalid_argument("nothing to write: give --out and/or --png");
  std::string written;
  if (!exr_file.empty()) {
    write_exr(image, exr_file, half ? ExrPixelType::half : ExrPixelType::float32);
    written = exr_file + pixel_type_name(half);
  }
  if (!png_file.empty()) {
    write_png(image, png_file, DisplaySettings{exposure, kToneMaps.at(tone_map)});
    written += (written.empty() ? "" : ", ") + png_file + " (sRGB, " + tone_map + ")";
  }
  return written;
}

std::string ImageOutputs::write(const Image& image, const TermLayers& terms) const {
  if (aov_file.empty()) return write(image);
  const std::string written = exr_file.empty() && png_file.empty() ? "" : write(image) + ", ";
  write_layered_exr({{"", &image, true},
                     {"ambient", &terms.ambient, false},
                     {"diffuse", &terms.diffuse, false},
                     {"specular", &terms.specular, false}},
                    aov_file, half ? ExrPixelType::half : ExrPixelType::float32);
  return written + aov_file + " (ambient, diffuse, specular + combined, " + (half ? "half" : "float32") + ")";
}

}  // namespace phongcl::cli
