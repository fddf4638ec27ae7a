// phongcl::Relighter (include/phongcl/relighter.hpp): a scene and G-buffer handed to the shader
// engine (shading/phong_shader.h), which keeps the packed G-buffer, the tables and the kernel on
// the device from one shade() to the next; the Relighter says what changed in between.
#include <phongcl/relighter.hpp>

#include <mutex>
#include <optional>
#include <stdexcept>

#include "cl/compute_context.h"
#include "cl/program_cache.h"
#include "gbuffer/material_check.h"
#include "scene/area_light_json.h"
#include "scene/environment_json.h"
#include "scene/scene_check.h"
#include "shading/frame_memory.h"
#include "shading/phong_shader.h"
#include "shading/recipe.h"

namespace phongcl {

namespace {

ShadeOptions shade_options(const RelighterOptions& options) {
  ShadeOptions shade{options.precision, options.specialise};
  shade.lanes = options.lanes;
  shade.culling = options.culling;
  shade.tile_size = options.tile_size;
  shade.write_terms = options.terms;
  shade.max_tile_pixels = options.max_tile_pixels;
  shade.shadows = options.shadows;
  return shade;
}

}  // namespace

void check_options(const RelighterOptions& options) {
  const int lanes = options.lanes;
  if (lanes != 0 && lanes != 1 && lanes != 2 && lanes != 4 && lanes != 8 && lanes != 16)
    throw std::invalid_argument("lanes must be 0 (the device's choice), 1, 2, 4, 8 or 16 (got " + std::to_string(lanes) + ")");
  if (options.tile_size < 1 || options.tile_size > 1024)
    throw std::invalid_argument("tile size must be in [1, 1024] pixels (got " + std::to_string(options.tile_size) + ")");
  check_shadow_settings(options.shadows);
}

struct Relighter::State {
  explicit State(const RelighterOptions& options)
      : options(shade_options(options)),
        cache(ProgramCache::default_directory()),
        engine(make_compute_context(pick_device(options.device)), cache) {}

  const DeviceInfo& device() const { return engine.compute().device.info; }

  // The frame so far; std::logic_error before set_frame.
  struct Frame {
    Scene scene;
    GBuffer gbuffer;
    Recipe recipe;
    MaterialCheck material_check;  // of new material tables against this G-buffer
    std::optional<std::vector<MemoryNeed>> geometry_memory;  // counted when the recipe first traces objects
  };
  Frame& frame() {
    if (!current) throw std::logic_error("phongcl::Relighter: no frame yet (set_frame before shade)");
    return *current;
  }

  // The recipe for `scene` on the frame's G-buffer: the kernel is rebuilt only if its options change.
  Recipe recipe_for(const Scene& scene, const GBuffer& gbuffer) const {
    return make_recipe(scene, gbuffer, device(), options);
  }

  // What shading `scene` with `recipe` holds, against the memory left, before any of it is allocated.
  static void check_memory(const Scene& scene, const GBuffer& gbuffer, const Recipe& recipe,
                           std::optional<std::vector<MemoryNeed>>& geometry_memory) {
    if (!geometry_memory && recipe.shadows == ShadowMode::geometry)
      geometry_memory = geometry_memory_needs(scene, recipe);
    check_frame_memory(frame_memory_needs(gbuffer, recipe), geometry_memory.value_or(std::vector<MemoryNeed>{}));
  }

  // The frame's lights or materials changed: the recipe again (their counts are compiled in),
  // and the tables uploaded again at the next shade.
  void replace_scene(Scene next) {
    Frame& f = frame();
    Recipe recipe = recipe_for(next, f.gbuffer);
    check_memory(next, f.gbuffer, recipe, f.geometry_memory);
    f.recipe = std::move(recipe);
    f.scene = std::move(next);
    engine.forget_uniforms();
  }

  void shade_into(const FrameTargets& targets) {
    Frame& f = frame();
    last_report = engine.shade_into(f.scene, f.gbuffer, f.recipe, targets, options.max_tile_pixels);
  }

  std::mutex mutex;
  ShadeOptions options;
  ProgramCache cache;  // before the engine, which refers to it
  PhongShader engine;
  std::optional<Frame> current;
  ShadeReport last_report;
};

Relighter::Relighter(const Scene& scene, const GBuffer& gbuffer, const RelighterOptions& options)
    : Relighter(scene, GBuffer(gbuffer), options) {}

Relighter::Relighter(const Scene& scene, GBuffer&& gbuffer, const RelighterOptions& options) : Relighter(options) {
  set_frame(scene, std::move(gbuffer));
}

Relighter::Relighter(const RelighterOptions& options) {
  check_options(options);
  state_ = std::make_unique<State>(options);
}

Relighter::~Relighter() = default;
Relighter::Relighter(Relighter&&) noexcept = default;
Relighter& Relighter::operator=(Relighter&&) noexcept = default;

void Relighter::set_frame(const Scene& scene, GBuffer&& gbuffer) {
  if (!scene.color_space.empty())
    throw std::invalid_argument("the scene's colours are in '" + scene.color_space +
                                "': convert them to the working space first (phongcl::convert_scene_colors)");
  check_material_table(scene.materials);
  check_lights(scene.lights, scene.materials.size());
  check_area_lights(scene.area_lights);
  if (scene.environment) check_environment_light(*scene.environment);
  const std::lock_guard lock(state_->mutex);
  phongcl::check_materials(gbuffer, scene.materials.size());
  Recipe recipe = state_->recipe_for(scene, gbuffer);
  std::optional<std::vector<MemoryNeed>> geometry_memory;
  State::check_memory(scene, gbuffer, recipe, geometry_memory);
  state_->current = State::Frame{scene, std::move(gbuffer), std::move(recipe), MaterialCheck(scene.materials.size()),
                                 std::move(geometry_memory)};
  state_->engine.forget_gbuffer();
  state_->engine.forget_uniforms();
}

void Relighter::set_lights(const std::vector<Light>& lights) {
  const std::lock_guard lock(state_->mutex);
  State::Frame& frame = state_->frame();
  check_lights(lights, frame.scene.materials.size());
  Scene next = frame.scene;
  next.lights = lights;
  state_->replace_scene(std::move(next));
}

void Relighter::set_area_lights(const std::vector<AreaLight>& lights) {
  check_area_lights(lights);
  const std::lock_guard lock(state_->mutex);
  Scene next = state_->frame().scene;
  next.area_lights = lights;
  state_->replace_scene(std::move(next));
}

void Relighter::set_environment(const std::optional<EnvironmentLight>& environment) {
  if (environment) check_environment_light(*environment);
  const std::lock_guard lock(state_->mutex);
  Scene next = state_->frame().scene;
  next.environment = environment;
  state_->replace_scene(std::move(next));
}

void Relighter::set_materials(const std::vector<Material>& materials) {
  check_material_table(materials);
  const std::lock_guard lock(state_->mutex);
  State::Frame& frame = state_->frame();
  frame.material_check.check(frame.gbuffer, materials.size());
  Scene next = frame.scene;
  next.materials = materials;
  state_->replace_scene(std::move(next));
}

void Relighter::set_camera_eye(const glm::dvec3& eye) {
  if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z))
    throw std::invalid_argument("camera eye: must be finite");
  const std::lock_guard lock(state_->mutex);
  State::Frame& frame = state_->frame();
  if (eye == frame.scene.camera.eye) return;
  frame.scene.camera.eye = eye;  // the engine re-packs: positions and point lights are stored relative to the eye
  state_->engine.forget_uniforms();
}

Image Relighter::shade() {
  const std::lock_guard lock(state_->mutex);
  Image image = image_like(state_->frame().gbuffer);
  state_->shade_into({image.rgba.data()});
  return image;
}

Image Relighter::shade(TermImages& terms) {
  const std::lock_guard lock(state_->mutex);
  if (!state_->options.write_terms)
    throw std::logic_error("phongcl::Relighter: shade(TermImages&) needs RelighterOptions::terms");
  const State::Frame& frame = state_->frame();
  const GBuffer& gbuffer = frame.gbuffer;
  Image image = image_like(gbuffer);
  const std::vector<std::string>& groups = frame.recipe.light_groups;
  terms = {image_like(gbuffer), image_like(gbuffer), image_like(gbuffer), groups,
           std::vector<Image>(groups.size(), image_like(gbuffer))};
  FrameTargets targets{image.rgba.data(), terms.ambient.rgba.data(), terms.diffuse.rgba.data(), terms.specular.rgba.data()};
  for (Image& group : terms.groups) targets.groups.push_back(group.rgba.data());
  state_->shade_into(targets);
  return image;
}

void Relighter::shade_into(float* rgba, std::size_t floats) {
  const std::lock_guard lock(state_->mutex);
  const GBuffer& gbuffer = state_->frame().gbuffer;
  const std::size_t expected = 4 * gbuffer.pixel_count();
  if (floats != expected)
    throw std::invalid_argument("shade_into: the buffer holds " + std::to_string(floats) + " floats, " +
                                std::to_string(expected) + " expected (4 x " + std::to_string(gbuffer.width) + " x " +
                                std::to_string(gbuffer.height) + ")");
  state_->shade_into({rgba});
}

int Relighter::width() const { return state_->current ? state_->current->gbuffer.width : 0; }
int Relighter::height() const { return state_->current ? state_->current->gbuffer.height : 0; }
const Scene& Relighter::scene() const { return state_->frame().scene; }
const GBuffer& Relighter::gbuffer() const { return state_->frame().gbuffer; }
const DeviceInfo& Relighter::device() const { return state_->device(); }

std::string Relighter::kernel_summary() const {
  const std::lock_guard lock(state_->mutex);
  return state_->frame().recipe.summary();
}

std::string Relighter::build_options() const {
  const std::lock_guard lock(state_->mutex);
  return state_->frame().recipe.build_options();
}

ShadeReport Relighter::last_report() const {
  const std::lock_guard lock(state_->mutex);
  return state_->last_report;
}

ShadeTimings Relighter::last_timings() const { return last_report().timings; }

std::vector<DeviceInfo> available_devices() {
  std::vector<DeviceInfo> infos;
  for (const Device& device : list_devices()) infos.push_back(device.info);
  return infos;
}

}  // namespace phongcl
