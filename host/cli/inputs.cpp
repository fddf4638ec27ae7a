#include "cli/inputs.h"

#include "common/error.h"

namespace phongcl::cli {

void SceneInputs::add_options(CLI::App& command) {
  command.add_option("--scene", scene_file, "Scene file (JSON)")->required();
  command.add_option("--gbuffer", gbuffer_file, "G-buffer EXR (default: the scene's \"gbuffer\" entry)");
}

Scene SceneInputs::load_scene() const { return phongcl::load_scene(scene_file); }

GBuffer SceneInputs::load_gbuffer(const Scene& scene) const {
  if (!gbuffer_file.empty()) return read_gbuffer(gbuffer_file);
  if (scene.gbuffer.empty()) throw InputError(scene.source, "no G-buffer: give --gbuffer or a \"gbuffer\" entry in the scene");
  return read_gbuffer(scene.gbuffer);
}

}  // namespace phongcl::cli
