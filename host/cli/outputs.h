#pragma once
// The --out/--half/--png options that shade and reference share, the display options of the PNG
// (--display, --view, --look, --exposure), and shade's --aov (the ambient, diffuse and specular
// terms as layers of one EXR).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "color/color_config.h"
#include "color/display.h"
#include "common/same_file.h"
#include "image/image.h"
#include "shading/shade_stats.h"

namespace phongcl {
struct Scene;
}

namespace phongcl::cli {

// --display, --view, --look, --exposure (and --tonemap, --view's old name) into `settings`.
void add_display_options(CLI::App& command, DisplaySettings& settings, std::string& tone_map);
// The settings with --tonemap applied.
DisplaySettings with_tone_map(DisplaySettings settings, const std::string& tone_map);

struct SceneInputs;

// Fails before any work is done when `file` could not be written: a missing or read-only
// directory, a directory where the file should be, a name longer than its file system allows.
void check_destination(const std::filesystem::path& file);

struct ImageOutputs {
  std::string exr_file, png_file, aov_file;
  bool half = false;
  DisplaySettings display;  // of the PNG; its background is each frame's scene's
  std::string tone_map;     // --tonemap: the old name of --view
  bool exr_background = false;  // keep the shader's background colour where alpha is 0 in EXRs
  ExrCompression compression = ExrCompression::zip;  // of the EXRs; callers set it (shade: --compression or the input's)
  std::shared_ptr<const ColorConfig> color;  // the inputs' config (SceneInputs::color_config); callers set it

  void add_options(CLI::App& command);
  void add_aov_option(CLI::App& command);  // only for commands that can produce the terms
  bool wants_terms() const { return !aov_file.empty(); }
  // Throws (naming the file, or the display, view or look) when an output could not be written,
  // before any work is done.
  void check_destinations() const;
  // The files written (--out, --png, --aov), for refuse_shared_files.
  std::vector<NamedFile> named_files() const;
  // The files are replaced together (all new or all old, even if killed); returns
  // "lit.exr (float32), lit.png (sRGB, Filmic)". `background`: the scene's, under the PNG.
  std::string write(const Image& image, const glm::dvec3& background) const;
  // The same, plus --aov: layers ambient.*, diffuse.*, specular.*, group.<name>.* (R G B) and the
  // combined R G B A.
  std::string write(const Image& image, const glm::dvec3& background, const TermImages& terms) const;

 private:
  DisplayTransform display_transform(const glm::dvec3& background) const;
  ExrWriteOptions exr_options() const;
  std::string write_images(const Image& image, const glm::dvec3& background) const;  // --out and --png, inside the caller's batch
};

// Refuses (refuse_shared_files) a run whose output is one of its inputs or another output: the
// options' files, and with `scene` (parsed) its meshes and, without --gbuffer, its "gbuffer" entry,
// and the command's `other_inputs` (shade's --over).
void refuse_outputs_over_inputs(const SceneInputs& inputs, const ImageOutputs& outputs, const Scene* scene = nullptr,
                                std::vector<NamedFile> other_inputs = {});

}  // namespace phongcl::cli
