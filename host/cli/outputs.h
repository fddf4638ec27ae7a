#pragma once
// The --out/--half/--png/--exposure/--tonemap options that shade and reference share.
#include <string>

#include <CLI/CLI.hpp>

#include "image/image.h"

namespace phongcl::cli {

struct ImageOutputs {
  std::string exr_file, png_file;
  bool half = false;
  double exposure = 0.0;
  std::string tone_map = "reinhard";

  void add_options(CLI::App& command);
  // Each file is written atomically; returns "lit.exr (float32), lit.png" for the summary.
  std::string write(const Image& image) const;
};

}  // namespace phongcl::cli
