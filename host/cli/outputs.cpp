#include "cli/outputs.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "cli/inputs.h"
#include "common/atomic_file.h"
#include "common/error.h"

namespace phongcl::cli {

namespace {

std::string pixel_type_name(bool half) { return half ? " (half)" : " (float32)"; }

std::string display_name(const DisplayTransform& display) {
  return display.display() + ", " + display.view() + (display.look().empty() ? "" : ", " + display.look());
}

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
  if (!png_file.empty()) display_transform(glm::dvec3(0.0));  // names in the config, finite exposure
}

std::vector<NamedFile> ImageOutputs::named_files() const {
  std::vector<NamedFile> files;
  for (const auto& [option, file] : {std::pair{"--out", &exr_file}, std::pair{"--png", &png_file}, std::pair{"--aov", &aov_file}})
    if (!file->empty()) files.push_back({option, *file, true});
  return files;
}

void add_display_options(CLI::App& command, DisplaySettings& settings, std::string& tone_map) {
  command.add_option("--display", settings.display, "PNG display of the OCIO config (default: the config's; phongcl colors lists them)");
  command.add_option("--view", settings.view, "PNG view of the display (default: the display's; the built-in config's: "
                                              "reinhard, aces, clamp; Blender's: Filmic, Standard, ...)");
  command.add_option("--look", settings.look, "PNG look of the OCIO config, before the view (default: none)");
  command
      .add_option("--exposure", settings.exposure_stops,
                  "PNG exposure in stops: working-space values are scaled by 2^exposure before the look and view "
                  "(default 0, within +-40)")
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
  command.add_option("--tonemap", tone_map, "The same as --view (its name before OCIO)")->excludes("--view");
}

DisplaySettings with_tone_map(DisplaySettings settings, const std::string& tone_map) {
  if (!tone_map.empty()) settings.view = tone_map;
  return settings;
}

void ImageOutputs::add_options(CLI::App& command) {
  command.add_option("--out", exr_file, "Output EXR (R G B A, premultiplied: RGB 0 where alpha is 0)");
  command.add_flag("--half", half, "Write EXRs as half instead of float32");
  command.add_flag("--exr-background", exr_background,
                   "Keep the scene's background colour where alpha is 0 in EXRs (as phongcl wrote them before; "
                   "a compositor's over adds it to the plate)");
  command.add_option("--png", png_file, "Also write an 8-bit PNG preview: the image over the scene's background, "
                                        "through the config's display and view");
  add_display_options(command, display, tone_map);
}

void ImageOutputs::add_aov_option(CLI::App& command) {
  command.add_option("--aov", aov_file,
                     "Also write a multilayer EXR: ambient.RGB, diffuse.RGB, specular.RGB and the combined R G B A");
}

DisplayTransform ImageOutputs::display_transform(const glm::dvec3& background) const {
  if (!color) throw std::logic_error("ImageOutputs: no colour config set");
  DisplaySettings settings = with_tone_map(display, tone_map);
  settings.background = background;
  return DisplayTransform(*color, settings);
}

ExrWriteOptions ImageOutputs::exr_options() const {
  ExrWriteOptions options;
  options.type = half ? ExrPixelType::half : ExrPixelType::float32;
  options.compression = compression;
  options.keep_color_where_transparent = exr_background;
  if (color) options.chromaticities = color->working_chromaticities();
  return options;
}

// Every output is written to a temporary first and all are renamed together (AtomicBatch), so a
// failure or a kill leaves either all the old files or all the new ones, never a mix.
std::string ImageOutputs::write(const Image& image, const glm::dvec3& background) const {
  AtomicBatch batch;
  const std::string written = write_images(image, background);
  batch.commit();
  return written;
}

std::string ImageOutputs::write(const Image& image, const glm::dvec3& background, const TermImages& terms) const {
  if (aov_file.empty()) return write(image, background);
  AtomicBatch batch;
  std::vector<ExrLayer> layers = {{"", &image, true},
                                  {"ambient", &terms.ambient, false},
                                  {"diffuse", &terms.diffuse, false},
                                  {"specular", &terms.specular, false}};
  for (std::size_t g = 0; g < terms.groups.size(); ++g) layers.push_back({"group." + terms.group_names[g], &terms.groups[g], false});
  write_layered_exr(layers, aov_file, exr_options());
  const std::string groups = terms.groups.empty() ? "" : ", " + std::to_string(terms.groups.size()) + " light groups";
  const std::string aov_written =
      aov_file + " (ambient, diffuse, specular" + groups + " + combined, " + (half ? "half" : "float32") + ")";
  const std::string written =
      exr_file.empty() && png_file.empty() ? aov_written : write_images(image, background) + ", " + aov_written;
  batch.commit();
  return written;
}

std::string ImageOutputs::write_images(const Image& image, const glm::dvec3& background) const {
  if (exr_file.empty() && png_file.empty()) throw std::invalid_argument("nothing to write: give --out and/or --png");
  std::string png_written;
  if (!png_file.empty()) {
    const DisplayTransform transform = display_transform(background);
    write_png(image, png_file, transform);
    png_written = png_file + " (" + display_name(transform) + ")";
  }
  if (exr_file.empty()) return png_written;
  write_exr(image, exr_file, exr_options());
  return exr_file + pixel_type_name(half) + (png_written.empty() ? "" : ", " + png_written);
}

void refuse_outputs_over_inputs(const SceneInputs& inputs, const ImageOutputs& outputs, const Scene* scene,
                                std::vector<NamedFile> other_inputs) {
  std::vector<NamedFile> files = inputs.named_files(scene);
  for (NamedFile& file : other_inputs) files.push_back(std::move(file));
  for (NamedFile& file : outputs.named_files()) files.push_back(std::move(file));
  refuse_shared_files(files);
}

}  // namespace phongcl::cli
