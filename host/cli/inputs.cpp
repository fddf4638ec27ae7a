#include "cli/inputs.h"

#include "common/error.h"
#include "gbuffer/layouts.h"
#include "raycast/depth_reconstruction.h"
#include "scene/camera_space.h"

namespace phongcl::cli {

void SceneInputs::add_options(CLI::App& command) {
  command.add_option("--scene", scene_file, "Scene file (JSON)")->required();
  command.add_option("--gbuffer", gbuffer_file, "G-buffer EXR (default: the scene's \"gbuffer\" entry)");
  command.add_option("--layout", layout, "G-buffer channel layout: auto (default), phongcl, blender or aov");
  command.add_option("--view-layer", view_layer, "Blender view layer to read (default: the file's only one, or ViewLayer)");
  command.add_option("--channel", channels,
                     "Map channels to a pass, e.g. position=Foo.X,Foo.Y,Foo.Z (passes: position, normal, depth, "
                     "material, alpha, ka, kd, ks, shininess); repeatable, overrides the layout");
  command.add_option("--space", space, "Space of the G-buffer's P and N: world (default) or camera (eye at origin, -Z forward)")
      ->check(CLI::IsMember({"world", "camera"}));
  command.add_option("--depth-convention", depth_convention,
                     "Depth pass meaning, when positions come from depth: distance (along the ray, default) or viewz")
      ->check(CLI::IsMember({"distance", "viewz"}));
  command.add_option("--max-pixels", max_pixels,
                     "Refuse G-buffers whose data window has more pixels, before allocating (default 268435456 = 16384^2)")
      ->check(CLI::PositiveNumber);
}

Scene SceneInputs::load_scene() const {
  const Scene scene = phongcl::load_scene(scene_file);
  return camera_space() ? to_camera_space(scene) : scene;
}

LoadedGBuffer SceneInputs::load_described_gbuffer(const Scene& scene) const {
  ReadOptions options;
  options.layout = parse_layout(layout);
  options.view_layer = view_layer;
  options.max_pixels = max_pixels;
  for (const auto& assignment : channels) {
    auto [pass, names] = parse_channel_assignment(assignment);
    options.channels[pass] = std::move(names);  // the last mapping of a pass wins
  }
  if (gbuffer_file.empty() && scene.gbuffer.empty())
    throw InputError(scene.source, "no G-buffer: give --gbuffer or a \"gbuffer\" entry in the scene");

  GBufferRead read = read_gbuffer(gbuffer_file.empty() ? scene.gbuffer : std::filesystem::path(gbuffer_file), options);
  std::string description = read.description;
  if (read.needs_positions_from_depth()) {
    const bool distance = depth_convention == "distance";
    positions_from_depth(read.gbuffer, read.depth, scene.camera,
                         distance ? DepthConvention::distance : DepthConvention::view_z);
    description += distance ? ", depth = distance along the ray" : ", depth = view-space z";
  }
  return {std::move(read.gbuffer), description};
}

}  // namespace phongcl::cli
