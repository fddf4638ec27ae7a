#include "shading/phong_shader.h"

#include <algorithm>
#include <chrono>

#include "cl/kernel_source.h"

namespace phongcl {

namespace {

using Clock = std::chrono::steady_clock;

double milliseconds(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double, std::milli>(end - start).count();
}

// Copies the kernel's term planes into the three term images, alpha from the combined image
// (premultiplied like it, so the terms still sum to it).
void copy_terms(cl::CommandQueue& queue, const cl::Buffer& terms, std::size_t stride, std::size_t first,
                std::size_t count, const Plane& coverage, const FrameTargets& targets) {
  const auto* planes = static_cast<const float*>(
      queue.enqueueMapBuffer(terms, CL_TRUE, CL_MAP_READ, 0, PHONGCL_TERM_PLANES * stride * sizeof(cl_float)));
  float* images[] = {targets.ambient, targets.diffuse, targets.specular};
  const float* combined = targets.rgba + 4 * first;
  for (int term = 0; term < 3; ++term) {
    float* out = images[term] + 4 * first;
    interleave(planes + 3 * term * stride, stride, count, 3, out);
    for (std::size_t t = 0; t < count; ++t) {
      out[4 * t + 3] = combined[4 * t + 3];
      if (!coverage.empty() && out[4 * t + 3] > 0.0f)
        for (int c = 0; c < 3; ++c) out[4 * t + c] *= coverage[first + t];
    }
  }
  queue.enqueueUnmapMemObject(terms, const_cast<float*>(planes));
}

void describe_recipe(const Recipe& recipe, ShadeReport& report) {
  report.kernel_summary = recipe.summary();
  report.recipe_reasons = recipe.reasons;
  report.build_options = recipe.build_options();
  report.point_lights = recipe.point_lights;
  report.spot_lights = recipe.spot_lights;
  report.directional_lights = recipe.directional_lights;
  report.culled = recipe.tiled;
}

}  // namespace

ShadeResult PhongShader::shade(const Scene& scene, const GBuffer& gbuffer, const ShadeOptions& options) {
  check_materials(gbuffer, scene.materials.size());
  ShadeResult result;
  result.recipe = make_recipe(scene, gbuffer, compute_.device.info, options);
  result.image = image_like(gbuffer);
  FrameTargets targets{result.image.pixel(0)};
  if (result.recipe.write_terms) {
    result.terms = {image_like(gbuffer), image_like(gbuffer), image_like(gbuffer)};
    targets = {result.image.pixel(0), result.terms.ambient.pixel(0), result.terms.diffuse.pixel(0),
               result.terms.specular.pixel(0)};
  }
  forget_gbuffer();
  forget_uniforms();
  static_cast<ShadeReport&>(result) = shade_into(scene, gbuffer, result.recipe, targets, options.max_tile_pixels);
  return result;
}

const cl::Kernel& PhongShader::kernel_for(ShadeReport& report) {
  if (kernel_ && kernel_options_ == report.build_options) return *kernel_;
  const BuiltProgram built = cache_.build(compute_, load_kernel_source("phong.cl"), report.build_options);
  kernel_ = phong_kernel(built.program);
  kernel_options_ = report.build_options;
  report.cache = built.outcome;
  report.timings.build_ms = built.build_milliseconds;
  report.timings.rebuilt = true;
  return *kernel_;
}

TileCuller& PhongShader::culler_for(const std::string& build_options) {
  if (!culler_ || culler_options_ != build_options) {
    culler_ = std::make_unique<TileCuller>(compute_, cache_, build_options);
    culler_options_ = build_options;
  }
  return *culler_;
}

ShadeReport PhongShader::shade_into(const Scene& scene, const GBuffer& gbuffer, const Recipe& recipe,
                                    const FrameTargets& targets, std::size_t max_tile_pixels) {
  ShadeReport report;
  describe_recipe(recipe, report);
  report.disk_cache_directory = cache_.disk_directory().string();
  report.disk_cache_problem = cache_.disk_problem();
  const cl::Kernel& kernel = kernel_for(report);

  const auto start = Clock::now();
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;
  TileLayout tiles = tile_layout(gbuffer.width, gbuffer.height, recipe.tile_size);
  TileCuller* culler = recipe.tiled ? &culler_for(report.build_options) : nullptr;

  const std::size_t pixels = gbuffer.pixel_count();
  const bool half = recipe.precision == Precision::half_storage;
  const std::size_t lanes = static_cast<std::size_t>(recipe.lanes);
  // Every plane holds `stride` values, a multiple of the kernel's lanes; tiles are padded to it.
  const std::size_t stride = round_up(tile_pixels(compute_.device.info, recipe, pixels, max_tile_pixels), lanes);
  const std::size_t plane_bytes = stride * recipe.plane_count() * (half ? sizeof(cl_half) : sizeof(cl_float));
  const PackTarget pack_target{planes_.at_least(context, plane_bytes),
                               material_index_.at_least(context, stride * sizeof(cl_int)), stride};
  const cl::Buffer& output = output_.at_least(context, PHONGCL_OUTPUT_PLANES * stride * sizeof(cl_float));
  const cl::Buffer& terms =
      terms_.at_least(context, (recipe.write_terms ? PHONGCL_TERM_PLANES * stride : 1) * sizeof(cl_float));
  if (!uniforms_ || uniforms_options_ != report.build_options || uniforms_stride_ != stride) {
    const auto upload_start = Clock::now();
    uniforms_ = upload_uniforms(context, pack_uniforms(scene, recipe), stride);
    uniforms_options_ = report.build_options;
    uniforms_stride_ = stride;
    report.timings.upload_ms += milliseconds(upload_start, Clock::now());
  }
  const DeviceUniforms& uniforms = *uniforms_;
  // One launch keeps its packed G-buffer for the next frame; tiles overwrite each other's.
  const PackedFor wanted{scene.camera.eye, recipe.precision, recipe.plane_count(), stride};
  const bool resident = stride >= pixels;
  if (!resident || (packed_ && packed_->key != wanted)) packed_.reset();
  std::size_t flushed_to_zero = 0;

  for (std::size_t first = 0; first < pixels; first += stride, ++report.tiles) {
    const std::size_t count = std::min(stride, pixels - first);
    const std::size_t padded = round_up(count, lanes);
    if (!packed_) {
      const PackedTile packed =
          pack_into_mapped(queue, pack_target, gbuffer, scene.camera.eye, recipe, first, count, padded);
      report.counts += packed.counts;
      flushed_to_zero += packed.flushed_to_zero;
      report.timings.pack_ms += packed.pack_ms;
      report.timings.upload_ms += packed.upload_ms;
      report.timings.gbuffer_uploaded = true;
      if (resident) packed_ = PackedFrame{wanted, packed.counts, packed.flushed_to_zero};
    } else {
      report.counts = packed_->counts;
      flushed_to_zero = packed_->flushed_to_zero;
    }

    tiles.grid.first_pixel = static_cast<cl_uint>(first);
    const CullingStats culled = culler ? culler->cull(pack_target.planes, stride, pack_target.material_index, padded,
                                                      tiles, uniforms.point_bounds, uniforms.scalars.point_count)
                                       : CullingStats{};
    report.culling += culled;
    const TileLists culled_lists =
        culler ? TileLists{culler->offsets(), culler->counts(), culler->lights(), tiles.grid} : TileLists{};
    const cl::Event launched =
        launch_phong(kernel, queue, {pack_target.planes, pack_target.material_index, output, terms}, uniforms, padded,
                     recipe.lanes, culler ? &culled_lists : nullptr);

    cl::Event map_output;
    const auto* shaded = static_cast<const float*>(queue.enqueueMapBuffer(
        output, CL_TRUE, CL_MAP_READ, 0, PHONGCL_OUTPUT_PLANES * stride * sizeof(cl_float), nullptr, &map_output));
    const auto copy_start = Clock::now();
    interleave(shaded, stride, count, PHONGCL_OUTPUT_PLANES, targets.rgba + 4 * first);
    premultiply_by_coverage(gbuffer.coverage, first, count, targets.rgba + 4 * first);
    const double copy_ms = milliseconds(copy_start, Clock::now());
    queue.enqueueUnmapMemObject(output, const_cast<float*>(shaded));
    if (recipe.write_terms && targets.ambient) copy_terms(queue, terms, stride, first, count, gbuffer.coverage, targets);
    queue.finish();

    report.timings.kernel_ms += event_milliseconds(launched) + culled.culling_ms;
    report.timings.download_ms += event_milliseconds(map_output) + copy_ms;
  }
  report.timings.total_ms = milliseconds(start, Clock::now());
  if (flushed_to_zero > 0) {
    report.warnings.push_back(std::to_string(flushed_to_zero) +
                              " non-zero G-buffer values were below half's smallest subnormal (6e-8) and became 0 "
                              "in --precision half-storage");
  }
  return report;
}

}  // namespace phongcl
