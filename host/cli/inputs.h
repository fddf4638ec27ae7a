#pragma once
// The scene and G-buffer options that shade, reference and bench share: --scene/--gbuffer, how
// to read a renderer's G-buffer (--layout, --view-layer, --channel, --space, --depth-convention,
// --kd-from, --ks-from), and the colour spaces in (--ocio, --blender, --gbuffer-space).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "color/color_config.h"
#include "common/same_file.h"
#include "gbuffer/gbuffer.h"
#include "gbuffer/layouts.h"
#include "scene/scene.h"

namespace phongcl::cli {

struct LoadedGBuffer {
  GBuffer gbuffer;
  std::string layout;  // what was read, for the summary: "blender (view layer 'ViewLayer': ...)"
  std::vector<std::string> warnings;
  std::string beauty;  // the source of gbuffer.beauty ("Combined"), empty without one
};

struct SceneInputs {
  std::string scene_file;
  std::string gbuffer_file;  // empty: the scene's "gbuffer" entry
  std::string layout = "auto";
  std::string view_layer;
  std::vector<std::string> channels;  // "position=Foo.X,Foo.Y,Foo.Z", ...
  std::string space = "world";
  std::string depth_convention = "auto";
  std::string kd_from = "auto", ks_from = "auto";
  std::uint64_t max_pixels = ReadOptions{}.max_pixels;
  std::string ocio;           // --ocio: "", "builtin", "blender" or a config file (color/color_config.h)
  std::string blender;        // --blender: the Blender executable whose config --ocio blender loads
  std::string gbuffer_space;  // --gbuffer-space: the colour passes' space; empty: the working space

  void add_options(CLI::App& command);
  // The --ocio config, loaded at the first call (make it before starting threads); copies of these
  // inputs share it.
  std::shared_ptr<const ColorConfig> color_config() const;
  bool camera_space() const { return space == "camera"; }
  // The files read, for refuse_shared_files: --scene and --gbuffer; given the parsed scene, the
  // mesh files its objects name and, without --gbuffer, its "gbuffer" entry.
  std::vector<NamedFile> named_files(const Scene* scene = nullptr) const;
  // --gbuffer, else the scene's "gbuffer" entry (InputError when neither names a file).
  std::filesystem::path gbuffer_path(const Scene& scene) const;
  // The scene file with its colours in the working space; without a "camera", the G-buffer
  // header's (gbuffer/file_camera.h); with --space camera, seen from its camera (scene/camera_space.h).
  Scene load_scene() const;
  // Reads the G-buffer in the chosen layout, its colour passes into the working space, and where it
  // has depth but no position, rebuilds positions from depth and scene.camera (so call it with the
  // scene load_scene() returned).
  // Throws InputError when neither --gbuffer nor the scene's "gbuffer" entry names a file.
  // `with_beauty`: also the renderer's own image (GBuffer::beauty), where the file has one.
  LoadedGBuffer load_described_gbuffer(const Scene& scene, bool with_beauty = false) const;
  GBuffer load_gbuffer(const Scene& scene) const { return load_described_gbuffer(scene).gbuffer; }

 private:
  mutable std::shared_ptr<const ColorConfig> color_;
};

}  // namespace phongcl::cli
