// phongcl::Relighter (include/phongcl/relighter.hpp): the G-buffer stays packed in device memory;
// each shade() uploads what changed since the last one, launches, and copies the output out.
#include <phongcl/relighter.hpp>

#include <chrono>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "cl/compute_context.h"
#include "cl/kernel_source.h"
#include "cl/program_cache.h"
#include "scene/scene_check.h"
#include "shading/pack.h"
#include "shading/phong_launch.h"
#include "shading/recipe.h"

namespace phongcl {

namespace {

using Clock = std::chrono::steady_clock;

double milliseconds(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double, std::milli>(end - start).count();
}

}  // namespace

struct Relighter::State {
  State(const Scene& scene_in, GBuffer&& gbuffer_in, const RelighterOptions& options)
      : scene(scene_in),
        gbuffer(std::move(gbuffer_in)),
        shade_options{options.precision, options.specialise},
        compute(make_compute_context(pick_device(options.device))),
        cache(ProgramCache::default_directory()) {
    shade_options.lanes = options.lanes;
    phongcl::check_materials(gbuffer, scene.materials.size());
    update_recipe();
    const std::size_t pixels = gbuffer.pixel_count();
    if (tile_pixels(compute.device.info, *recipe, pixels, 0) < pixels)
      throw std::runtime_error("a " + std::to_string(gbuffer.width) + "x" + std::to_string(gbuffer.height) +
                               " G-buffer does not fit one allocation of " + compute.device.info.name +
                               "; phongcl shade shades it in tiles");
    stride = round_up(pixels, static_cast<std::size_t>(recipe->lanes));
    const bool half = recipe->precision == Precision::half_storage;
    const std::size_t plane_bytes = stride * recipe->plane_count() * (half ? sizeof(cl_half) : sizeof(cl_float));
    // ALLOC_HOST_PTR + map/unmap: on a CPU device packing writes straight into device memory.
    planes = cl::Buffer(compute.context, CL_MEM_READ_ONLY | CL_MEM_ALLOC_HOST_PTR, plane_bytes);
    material_index = cl::Buffer(compute.context, CL_MEM_READ_ONLY | CL_MEM_ALLOC_HOST_PTR, stride * sizeof(cl_int));
    output = cl::Buffer(compute.context, CL_MEM_WRITE_ONLY | CL_MEM_ALLOC_HOST_PTR,
                        PHONGCL_OUTPUT_PLANES * stride * sizeof(cl_float));
    unused_terms = cl::Buffer(compute.context, CL_MEM_WRITE_ONLY, sizeof(cl_float));
  }

  // A new recipe from the scene as it is now; the program is fetched only if its options changed.
  void update_recipe() {
    Recipe next = make_recipe(scene, gbuffer, compute.device.info, shade_options);
    if (recipe && next.build_options() == recipe->build_options()) return;
    recipe = std::move(next);
    kernel.reset();
  }

  void pack_gbuffer(RelightTimings& timings) {
    const auto start = Clock::now();
    const std::size_t pixels = gbuffer.pixel_count();
    const bool half = recipe->precision == Precision::half_storage;
    const std::size_t plane_bytes = stride * recipe->plane_count() * (half ? sizeof(cl_half) : sizeof(cl_float));
    cl::CommandQueue& queue = compute.queue;
    void* mapped_planes = queue.enqueueMapBuffer(planes, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, plane_bytes);
    auto* mapped_index = static_cast<cl_int*>(
        queue.enqueueMapBuffer(material_index, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, stride * sizeof(cl_int)));
    std::vector<float> half_staging(half ? stride * recipe->plane_count() : 0);
    float* float_planes = half ? half_staging.data() : static_cast<float*>(mapped_planes);
    try {
      pack_tile(gbuffer, scene.camera.eye, *recipe, 0, pixels, stride, stride, float_planes, mapped_index);
      if (half)
        convert_planes_to_half(gbuffer, *recipe, 0, stride, stride, float_planes,
                               static_cast<std::uint16_t*>(mapped_planes));
    } catch (...) {
      queue.enqueueUnmapMemObject(planes, mapped_planes);
      queue.enqueueUnmapMemObject(material_index, mapped_index);
      queue.finish();
      throw;
    }
    timings.pack_ms += milliseconds(start, Clock::now());
    cl::Event unmap_planes, unmap_index;
    queue.enqueueUnmapMemObject(planes, mapped_planes, nullptr, &unmap_planes);
    queue.enqueueUnmapMemObject(material_index, mapped_index, nullptr, &unmap_index);
    queue.finish();
    timings.upload_ms += event_milliseconds(unmap_planes) + event_milliseconds(unmap_index);
    timings.gbuffer_uploaded = true;
    gbuffer_stale = false;
  }

  void shade_into(float* rgba) {
    const auto start = Clock::now();
    RelightTimings timings;
    if (!kernel) {
      const BuiltProgram built = cache.build(compute, load_kernel_source("phong.cl"), recipe->build_options());
      kernel = phong_kernel(built.program);
      timings.build_ms = built.build_milliseconds;
      timings.rebuilt = true;
    }
    const auto frame_start = Clock::now();
    if (gbuffer_stale) pack_gbuffer(timings);
    if (!uniforms) {
      const auto pack_start = Clock::now();
      uniforms = upload_uniforms(compute.context, pack_uniforms(scene), stride);
      timings.upload_ms += milliseconds(pack_start, Clock::now());
    }
    cl::CommandQueue& queue = compute.queue;
    const cl::Event launched = launch_phong(*kernel, queue, {planes, material_index, output, unused_terms},
                                            *uniforms, stride, recipe->lanes);
    cl::Event map_output;
    const auto* shaded = static_cast<const float*>(queue.enqueueMapBuffer(
        output, CL_TRUE, CL_MAP_READ, 0, PHONGCL_OUTPUT_PLANES * stride * sizeof(cl_float), nullptr, &map_output));
    const auto copy_start = Clock::now();
    interleave(shaded, stride, gbuffer.pixel_count(), PHONGCL_OUTPUT_PLANES, rgba);
    premultiply_by_coverage(gbuffer.coverage, 0, gbuffer.pixel_count(), rgba);
    const double copy_ms = milliseconds(copy_start, Clock::now());
    queue.enqueueUnmapMemObject(output, const_cast<float*>(shaded));
    queue.finish();
    timings.kernel_ms = event_milliseconds(launched);
    timings.download_ms = event_milliseconds(map_output) + copy_ms;
    timings.total_ms = milliseconds(timings.rebuilt ? start : frame_start, Clock::now());
    last_timings = timings;
  }

  std::mutex mutex;
  Scene scene;
  GBuffer gbuffer;
  ShadeOptions shade_options;
  ComputeContext compute;
  ProgramCache cache;
  std::optional<Recipe> recipe;
  std::optional<cl::Kernel> kernel;           // phong_shade; empty: build before the next frame
  std::optional<DeviceUniforms> uniforms;     // empty: upload before the next frame
  bool gbuffer_stale = true;                  // pack and upload before the next frame
  std::size_t stride = 0;
  cl::Buffer planes, material_index, output, unused_terms;
  RelightTimings last_timings;
};

Relighter::Relighter(const Scene& scene, const GBuffer& gbuffer, const RelighterOptions& options)
    : Relighter(scene, GBuffer(gbuffer), options) {}

Relighter::Relighter(const Scene& scene, GBuffer&& gbuffer, const RelighterOptions& options)
    : state_(std::make_unique<State>(scene, std::move(gbuffer), options)) {}

Relighter::~Relighter() = default;
Relighter::Relighter(Relighter&&) noexcept = default;
Relighter& Relighter::operator=(Relighter&&) noexcept = default;

void Relighter::set_lights(const std::vector<Light>& lights) {
  check_lights(lights);
  const std::lock_guard lock(state_->mutex);
  state_->scene.lights = lights;
  state_->update_recipe();  // the light counts are compiled in
  state_->uniforms.reset();
}

void Relighter::set_materials(const std::vector<Material>& materials) {
  check_material_table(materials);
  const std::lock_guard lock(state_->mutex);
  phongcl::check_materials(state_->gbuffer, materials.size());
  state_->scene.materials = materials;
  state_->update_recipe();
  state_->uniforms.reset();
}

void Relighter::set_camera_eye(const glm::dvec3& eye) {
  if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z))
    throw std::invalid_argument("camera eye: must be finite");
  const std::lock_guard lock(state_->mutex);
  if (eye == state_->scene.camera.eye) return;
  state_->scene.camera.eye = eye;
  state_->gbuffer_stale = true;  // positions and point lights are stored relative to the eye
  state_->uniforms.reset();
}

Image Relighter::shade() {
  Image image = image_like(state_->gbuffer);
  const std::lock_guard lock(state_->mutex);
  state_->shade_into(image.rgba.data());
  return image;
}

void Relighter::shade_into(float* rgba, std::size_t floats) {
  const std::size_t expected = 4 * state_->gbuffer.pixel_count();
  if (floats != expected)
    throw std::invalid_argument("shade_into: the buffer holds " + std::to_string(floats) + " floats, " +
                                std::to_string(expected) + " expected (4 x " + std::to_string(width()) + " x " +
                                std::to_string(height()) + ")");
  const std::lock_guard lock(state_->mutex);
  state_->shade_into(rgba);
}

int Relighter::width() const { return state_->gbuffer.width; }
int Relighter::height() const { return state_->gbuffer.height; }
const Scene& Relighter::scene() const { return state_->scene; }
const DeviceInfo& Relighter::device() const { return state_->compute.device.info; }

std::string Relighter::kernel_summary() const {
  const std::lock_guard lock(state_->mutex);
  return state_->recipe->summary();
}

std::string Relighter::build_options() const {
  const std::lock_guard lock(state_->mutex);
  return state_->recipe->build_options();
}

RelightTimings Relighter::last_timings() const {
  const std::lock_guard lock(state_->mutex);
  return state_->last_timings;
}

std::vector<DeviceInfo> available_devices() {
  std::vector<DeviceInfo> infos;
  for (const Device& device : list_devices()) infos.push_back(device.info);
  return infos;
}

}  // namespace phongcl
