#pragma once
// The --scene/--gbuffer pair that shade, reference and bench share.
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "gbuffer/gbuffer.h"
#include "scene/scene.h"

namespace phongcl::cli {

struct SceneInputs {
  std::string scene_file;
  std::string gbuffer_file;  // empty: the scene's "gbuffer" entry

  void add_options(CLI::App& command);
  Scene load_scene() const;
  // Throws InputError when neither --gbuffer nor the scene's "gbuffer" entry names a file.
  GBuffer load_gbuffer(const Scene& scene) const;
};

}  // namespace phongcl::cli
