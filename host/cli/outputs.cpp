#include "cli/outputs.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "cli/inputs.h"
#include "common/atomic_file.h"
#include "common/error.h"

namespace phongcl::cli {

namespace {
const std::map<std::string, ToneMap> kToneMaps{{"clamp", ToneMap::clamp}, {"reinhard", ToneMap::reinhard}, {"aces", ToneMap::aces}};

std::string pixel_type_name(bool half) { return half ? " (half)" : " (float32)"; }

}  // namespace

void check_destination(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const fs::path directory = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) throw InputError(path, "cannot write: directory " + directory.string() + " does not exist");
  if (::access(directory.c_str(), W_OK) != 0) throw InputError(path, "cannot write: directory " + directory.string() + " is not writable");
  const long name_max = ::pathconf(directory.c_str(), _PC_NAME_MAX);
  if (name_max > 0 && path.filename().native().size() > static_cast<std::size_t>(name_max))
    throw InputError(path, "cannot write: the file name is " + std::to_string(path.filename().native().size()) +
                               " bytes, longer than the " + std::to_string(name_max) + " its file system allows");
  if (fs::is_directory(path, ec)) throw InputError(path, "cannot write: it is a directory");
}

void ImageOutputs::check_destinations() const {
  if (exr_file.empty() && png_file.empty() && aov_file.empty()) {
    throw std::invalid_argument("nothing to write: give --out, --png or --aov");
  }
  for (const std::string* file : {&exr_file, &png_file, &aov_file})
    if (!file->empty()) check_destination(*file);
}

std::vector<NamedFile> ImageOutputs::named_files() const {
  std::vector<NamedFile> files;
  for (const auto& [option, file] : {std::pair{"--out", &exr_file}, std::pair{"--png", &png_file}, std::pair{"--aov", &aov_file}})
    if (!file->empty()) files.push_back({option, *file, true});
  return files;
}

void ImageOutputs::add_options(CLI::App& command) {
  command.add_option("--out", exr_file, "Output EXR (R G B A)");
  command.add_flag("--half", half, "Write EXRs as half instead of float32");
  command.add_option("--png", png_file, "Also write an 8-bit sRGB PNG preview");
  command.add_option("--exposure", exposure, "PNG exposure in stops: values are scaled by 2^exposure (default 0, within +-40)")
      ->check(CLI::Validator(
          [](std::string& text) {
            char* end = nullptr;
            const double stops = std::strtod(text.c_str(), &end);  // "nan", "inf", "1e400" (as inf) too
            if (end == text.c_str() || *end != '\0') return std::string();  // not a number: CLI11 says so
            try {
              check_exposure(stops);
            } catch (const std::invalid_argument& error) {
              return std::string(error.what());
            }
            return std::string();
          },
          "STOPS"));
  command.add_option("--tonemap", tone_map,
                     "PNG tone map: clamp, reinhard (x/(1+x), default) or aces (Narkowicz's fit of the ACES filmic curve)")
      ->check(CLI::IsMember({"clamp", "reinhard", "aces"}));
}

void ImageOutputs::add_aov_option(CLI::App& command) {
  command.add_option("--aov", aov_file,
                     "Also write a multilayer EXR: ambient.RGB, diffuse.RGB, specular.RGB and the combined R G B A");
}

// Every output is written to a temporary first and all are renamed together (AtomicBatch), so a
// failure or a kill leaves either all the old files or all the new ones, never a mix.
std::string ImageOutputs::write(const Image& image) const {
  AtomicBatch batch;
  const std::string written = write_images(image);
  batch.commit();
  return written;
}

std::string ImageOutputs::write(const Image& image, const TermLayers& terms) const {
  if (aov_file.empty()) return write(image);
  AtomicBatch batch;
  write_layered_exr({{"", &image, true},
                     {"ambient", &terms.ambient, false},
                     {"diffuse", &terms.diffuse, false},
                     {"specular", &terms.specular, false}},
                    aov_file, half ? ExrPixelType::half : ExrPixelType::float32, compression);
  const std::string aov_written =
      aov_file + " (ambient, diffuse, specular + combined, " + (half ? "half" : "float32") + ")";
  const std::string written = exr_file.empty() && png_file.empty() ? aov_written : write_images(image) + ", " + aov_written;
  batch.commit();
  return written;
}

std::string ImageOutputs::write_images(const Image& image) const {
  if (exr_file.empty() && png_file.empty()) throw std::invalid_argument("nothing to write: give --out and/or --png");
  std::string png_written;
  if (!png_file.empty()) {
    write_png(image, png_file, DisplaySettings{exposure, kToneMaps.at(tone_map)});
    png_written = png_file + " (sRGB, " + tone_map + ")";
  }
  if (exr_file.empty()) return png_written;
  write_exr(image, exr_file, half ? ExrPixelType::half : ExrPixelType::float32, compression);
  return exr_file + pixel_type_name(half) + (png_written.empty() ? "" : ", " + png_written);
}

void refuse_outputs_over_inputs(const SceneInputs& inputs, const ImageOutputs& outputs, const Scene* scene) {
  std::vector<NamedFile> files = inputs.named_files(scene);
  for (NamedFile& file : outputs.named_files()) files.push_back(std::move(file));
  refuse_shared_files(files);
}

}  // namespace phongcl::cli
