#include "cli/inputs.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "cli/commands.h"
#include "color/color_conversion.h"
#include "common/error.h"
#include "gbuffer/file_camera.h"
#include "gbuffer/layouts.h"
#include "raycast/depth_reconstruction.h"
#include "scene/camera_space.h"
#include "scene/mesh_files.h"

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
  command.add_option("--ocio", ocio,
                     "OpenColorIO config: a config file, blender (an installed Blender's) or builtin (default: the OCIO "
                     "environment variable's, else builtin; phongcl colors lists what one holds)");
  command.add_option("--blender", blender, kBlenderOptionHelp);
  command.add_option("--gbuffer-space", gbuffer_space,
                     "Colour space of the G-buffer's colour passes (DiffCol, GlossCol, per-pixel ka/kd/ks, the beauty pass), "
                     "converted to the working space (default: already in it)");
}

std::shared_ptr<const ColorConfig> SceneInputs::color_config() const {
  if (!color_) color_ = std::make_shared<const ColorConfig>(ColorConfig::load(ocio, blender));
  return color_;
}

namespace {

ColourSource parse_colour_source(const std::string& text) {
  if (text == "pass") return ColourSource::pass;
  if (text == "table") return ColourSource::table;
  return ColourSource::layout_default;
}

}  // namespace

std::vector<NamedFile> SceneInputs::named_files(const Scene* scene) const {
  std::vector<NamedFile> files{{"--scene", scene_file}};
  if (!gbuffer_file.empty()) files.push_back({"--gbuffer", gbuffer_file});
  else if (scene != nullptr && !scene->gbuffer.empty()) files.push_back({"the scene's \"gbuffer\" entry", scene->gbuffer});
  if (scene != nullptr)
    for (const std::filesystem::path& mesh : mesh_files(scene->objects)) files.push_back(mesh_input(mesh));
  return files;
}

std::filesystem::path SceneInputs::gbuffer_path(const Scene& scene) const {
  if (gbuffer_file.empty() && scene.gbuffer.empty())
    throw InputError(scene.source, "no G-buffer: give --gbuffer or a \"gbuffer\" entry in the scene");
  return gbuffer_file.empty() ? scene.gbuffer : std::filesystem::path(gbuffer_file);
}

namespace {

Camera to_camera(const FileCamera& file) {
  Camera camera;
  camera.eye = {file.eye[0], file.eye[1], file.eye[2]};
  camera.look_at = camera.eye + glm::dvec3(file.forward[0], file.forward[1], file.forward[2]);
  camera.up = {file.up[0], file.up[1], file.up[2]};
  camera.fov_y_deg = file.fov_y_deg;
  camera.width = file.width;
  camera.height = file.height;
  return camera;
}

double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
  return glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)));
}

// Empty when the two agree to 1e-4 of the eye's distance from the origin (at least 1e-4) and 0.01
// degrees; else what differs.
std::string camera_difference(const Camera& scene, const Camera& file) {
  std::string text;
  const auto add = [&](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
  const double eye_apart = glm::length(scene.eye - file.eye);
  if (eye_apart > 1e-4 * std::max(1.0, glm::length(scene.eye))) add("eyes " + std::to_string(eye_apart) + " apart");
  if (const double a = angle_deg(scene.look_at - scene.eye, file.look_at - file.eye); a > 0.01)
    add("view directions " + std::to_string(a) + " degrees apart");
  if (const double a = angle_deg(scene.up - glm::dot(scene.up, glm::normalize(scene.look_at - scene.eye)) *
                                               glm::normalize(scene.look_at - scene.eye),
                                 file.up);
      a > 0.01)
    add("up " + std::to_string(a) + " degrees apart");
  if (std::abs(scene.fov_y_deg - file.fov_y_deg) > 0.01)
    add("fov_y " + std::to_string(scene.fov_y_deg) + " against " + std::to_string(file.fov_y_deg) + " degrees");
  if (scene.width != file.width || scene.height != file.height)
    add("size " + std::to_string(scene.width) + "x" + std::to_string(scene.height) + " against " +
        std::to_string(file.width) + "x" + std::to_string(file.height));
  return text;
}

}  // namespace

Scene SceneInputs::load_scene() const {
  Scene scene = phongcl::load_scene(scene_file);
  if (!scene.has_camera) {
    // The G-buffer's header may state the camera (gbuffer/file_camera.h).
    const auto file_camera = read_file_camera(gbuffer_path(scene));
    if (!file_camera)
      throw InputError(scene.source, "no \"camera\", and the G-buffer's header states none (worldToCamera and worldToNDC)");
    scene.camera = to_camera(*file_camera);
  }
  convert_scene_colors(scene, *color_config());
  return camera_space() ? to_camera_space(scene) : scene;
}

LoadedGBuffer SceneInputs::load_described_gbuffer(const Scene& scene, bool with_beauty) const {
  ReadOptions options;
  options.beauty = with_beauty;
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
  const std::filesystem::path file = gbuffer_path(scene);
  GBufferRead read = read_gbuffer(file, options);
  std::string& description = read.description;
  if (!gbuffer_space.empty()) {
    convert_gbuffer_colors(read.gbuffer, *color_config(), gbuffer_space);
    description += ", colour passes from " + gbuffer_space + " to " + color_config()->working_space();
  }
  if (const auto file_camera = read_file_camera(file)) {
    if (!scene.has_camera) {
      description += ", camera from the file's worldToCamera and worldToNDC";
    } else if (!camera_space()) {
      const std::string difference = camera_difference(scene.camera, to_camera(*file_camera));
      if (!difference.empty())
        read.warnings.push_back("the scene's camera and the file's (worldToCamera, worldToNDC) disagree: " + difference +
                                "; the scene's is used");
    }
  }
  if (read.needs_positions_from_depth()) {
    description += std::string(", depth = ") +
                   (read.depth_convention == DepthConvention::distance ? "distance along the ray" : "view-space z") +
                   " (" + read.depth_convention_reason + "; --depth-convention overrides)";
    positions_from_depth(read, scene.camera);
  }
  return {std::move(read.gbuffer), std::move(read.description), std::move(read.warnings), read.beauty};
}

}  // namespace phongcl::cli
