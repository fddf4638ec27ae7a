#pragma once
// The --out/--half/--png/--exposure/--tonemap options that shade and reference share, and shade's
// --aov (the ambient, diffuse and specular terms as layers of one EXR).
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/same_file.h"
#include "image/image.h"

namespace phongcl {
struct Scene;
}

namespace phongcl::cli {

struct SceneInputs;

// Fails before any work is done when `file` could not be written: a missing or read-only
// directory, a directory where the file should be, a name longer than its file system allows.
void check_destination(const std::filesystem::path& file);

// The terms of the combined image, for --aov.
struct TermLayers {
  const Image& ambient;
  const Image& diffuse;
  const Image& specular;
};

struct ImageOutputs {
  std::string exr_file, png_file, aov_file;
  bool half = false;
  double exposure = 0.0;
  std::string tone_map = "reinhard";
  ExrCompression compression = ExrCompression::zip;  // of the EXRs; callers set it (shade: --compression or the input's)

  void add_options(CLI::App& command);
  void add_aov_option(CLI::App& command);  // only for commands that can produce the terms
  bool wants_terms() const { return !aov_file.empty(); }
  // Throws (naming the file) when an output could not be written, before any work is done.
  void check_destinations() const;
  // The files written (--out, --png, --aov), for refuse_shared_files.
  std::vector<NamedFile> named_files() const;
  // The files are replaced together (all new or all old, even if killed); returns
  // "lit.exr (float32), lit.png".
  std::string write(const Image& image) const;
  // The same, plus --aov: layers ambient.*, diffuse.*, specular.* (R G B) and the combined R G B A.
  std::string write(const Image& image, const TermLayers& terms) const;

 private:
  std::string write_images(const Image& image) const;  // --out and --png, inside the caller's batch
};

// Refuses (refuse_shared_files) a run whose output is one of its inputs or another output: the
// options' files, and with `scene` (parsed, no --gbuffer) the scene's "gbuffer" entry.
void refuse_outputs_over_inputs(const SceneInputs& inputs, const ImageOutputs& outputs, const Scene* scene = nullptr);

}  // namespace phongcl::cli
