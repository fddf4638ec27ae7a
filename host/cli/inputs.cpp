#include "cli/inputs.h"

#include <tuple>

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
                     "Depth pass meaning, when positions come from depth: auto (the layout's: viewz for Blender, "
                     "default), distance (along the ray) or viewz (along the view axis)")
      ->check(CLI::IsMember({"auto", "distance", "viewz"}));
  for (auto [flag, value, pass] : {std::tuple{"--kd-from", &kd_from, "kd"}, std::tuple{"--ks-from", &ks_from, "ks"}})
    command.add_option(flag, *value, std::string("Where ") + pass + " comes from: auto (the layout's: for Blender kd from "
                                     "DiffCol, ks from the scene's table; default), pass or table")
        ->check(CLI::IsMember({"auto", "pass", "table"}));
  command.add_option("--max-pixels", max_pixels,
                     "Refuse G-buffers whose data window has more pixels, before allocating (default 268435456 = 16384^2)")
      ->check(CLI::PositiveNumber);
}

namespace {

ColourSource parse_colour_source(const std::string& text) {
  if (text == "pass") return ColourSource::pass;
  if (text == "table") return ColourSource::table;
  return ColourSource::layout_default;
}

}  // namespace

Scene SceneInputs::load_scene() const {
  const Scene scene = phongcl::load_scene(scene_file);
  return camera_space() ? to_camera_space(scene) : scene;
}

LoadedGBuffer SceneInputs::load_described_gbuffer(const Scene& scene) const {
  ReadOptions options;
  options.layout = parse_layout(layout);
  options.view_layer = view_layer;
  options.max_pixels = max_pixels;
  if (depth_convention != "auto")
    options.depth_convention = depth_convention == "viewz" ? DepthConvention::view_z : DepthConvention::distance;
  options.kd = parse_colour_source(kd_from);
  options.ks = parse_colour_source(ks_from);
  for (const auto& assignment : channels) {
    auto [pass, names] = parse_channel_assignment(assignment);
    options.channels[pass] = std::move(names);  // the last mapping of a pass wins
  }
  if (gbuffer_file.empty() && scene.gbuffer.empty())
    throw InputError(scene.source, "no G-buffer: give --gbuffer or a \"gbuffer\" entry in the scene");

  GBufferRead read = read_gbuffer(gbuffer_file.empty() ? scene.gbuffer : std::filesystem::path(gbuffer_file), options);
  std::string description = read.description;
  if (read.needs_positions_from_depth()) {
    positions_from_depth(read.gbuffer, read.depth, scene.camera, read.depth_convention);
    description += std::string(", depth = ") +
                   (read.depth_convention == DepthConvention::distance ? "distance along the ray" : "view-space z") +
                   " (" + read.depth_convention_reason + "; --depth-convention overrides)";
  }
  return {std::move(read.gbuffer), description, std::move(read.warnings)};
}

}  // namespace phongcl::cli
