#pragma once
// The --out/--half/--png/--exposure/--tonemap options that shade and reference share, and shade's
// --aov (the ambient, diffuse and specular terms as layers of one EXR).
#include <string>

#include <CLI/CLI.hpp>

#include "image/image.h"

namespace phongcl::cli {

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
  // The files are replaced together (all new or all old, even if killed); returns
  // "lit.exr (float32), lit.png".
  std::string write(const Image& image) const;
  // The same, plus --aov: layers ambient.*, diffuse.*, specular.* (R G B) and the combined R G B A.
  std::string write(const Image& image, const TermLayers& terms) const;

 private:
  std::string write_images(const Image& image) const;  // --out and --png, inside the caller's batch
};

}  // namespace phongcl::cli
