#include "shading/phong_shader.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "cl/kernel_source.h"
#include "common/host_threads.h"
#include "shading/shadow_buffers.h"

namespace phongcl {

namespace {

using Clock = std::chrono::steady_clock;

double milliseconds(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double, std::milli>(end - start).count();
}

// Planes of the kernel's terms buffer: ambient, diffuse, specular RGB, then each light group's RGB.
std::size_t term_planes(const Recipe& recipe) { return PHONGCL_TERM_PLANES + 3 * recipe.light_groups.size(); }

// Copies the kernel's term planes into the three term images and the light groups' images, alpha
// from the combined image (premultiplied like it, so the terms still sum to it).
void copy_terms(cl::CommandQueue& queue, const cl::Buffer& terms, std::size_t stride, std::size_t first,
                std::size_t count, const Plane& coverage, const FrameTargets& targets) {
  std::vector<float*> images = {targets.ambient, targets.diffuse, targets.specular};
  images.insert(images.end(), targets.groups.begin(), targets.groups.end());
  const auto* planes = static_cast<const float*>(
      queue.enqueueMapBuffer(terms, CL_TRUE, CL_MAP_READ, 0, 3 * images.size() * stride * sizeof(cl_float)));
  const float* combined = targets.rgba + 4 * first;
  // One pass over each image, on every core: a 1080p frame's terms are 100 MB to write.
  for (std::size_t term = 0; term < images.size(); ++term) {
    float* out = images[term] + 4 * first;
    const float* plane = planes + 3 * term * stride;
    for_each_core_range(count, 1 << 12, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t) {
        const float alpha = combined[4 * t + 3];
        const float scale = !coverage.empty() && alpha > 0.0f ? coverage[first + t] : 1.0f;
        for (int c = 0; c < 3; ++c) out[4 * t + c] = plane[c * stride + t] * scale;
        out[4 * t + 3] = alpha;
      }
    });
  }
  queue.enqueueUnmapMemObject(terms, const_cast<float*>(planes));
}

void describe_recipe(const Recipe& recipe, ShadeReport& report) {
  report.kernel_summary = recipe.summary();
  report.recipe_reasons = recipe.reasons();
  report.build_options = recipe.build_options();
  report.point_lights = recipe.point_lights;
  report.spot_lights = recipe.spot_lights;
  report.directional_lights = recipe.directional_lights;
  report.area_lights = recipe.area_lights;
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
    result.terms = {image_like(gbuffer), image_like(gbuffer), image_like(gbuffer), result.recipe.light_groups,
                    std::vector<Image>(result.recipe.light_groups.size(), image_like(gbuffer))};
    targets = {result.image.pixel(0), result.terms.ambient.pixel(0), result.terms.diffuse.pixel(0),
               result.terms.specular.pixel(0)};
    for (Image& group : result.terms.groups) targets.groups.push_back(group.pixel(0));
  }
  forget_gbuffer();
  forget_uniforms();
  static_cast<ShadeReport&>(result) = shade_into(scene, gbuffer, result.recipe, targets, options.max_tile_pixels);
  return result;
}

cl::Kernel& PhongShader::kernel_for(ShadeReport& report) {
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

ShadowCuller& PhongShader::shadow_culler_for(const std::string& build_options) {
  if (!shadow_culler_ || shadow_culler_options_ != build_options) {
    shadow_culler_ = std::make_unique<ShadowCuller>(compute_, cache_, build_options);
    shadow_culler_options_ = build_options;
  }
  return *shadow_culler_;
}

void PhongShader::prepare_shadows(const Scene& scene, const GBuffer& gbuffer, const Recipe& recipe,
                                  ShadeReport& report) {
  if (recipe.shadows == ShadowMode::off) return;
  const ShadowsFor wanted{scene.camera.eye, recipe.shadows, recipe.shadow_settings.steps,
                          recipe.shadow_settings.thickness, recipe.precision == Precision::half_storage};
  if (!shadows_ || shadows_->key != wanted)
    shadows_ = ResidentShadows{wanted, make_shadow_device(compute_.context, scene, gbuffer, recipe.shadows,
                                                          recipe.shadow_settings, wanted.half)};
  report.shadows = describe_shadows(recipe.shadows, recipe.shadow_casters, recipe.shadow_settings, shadows_->device);
}

PhongShader::FrameSetup PhongShader::prepare(const Scene& scene, const GBuffer& gbuffer, const Recipe& recipe,
                                             std::size_t max_tile_pixels, ShadeReport& report) {
  const cl::Context& context = compute_.context;
  const std::size_t pixels = gbuffer.pixel_count();
  const bool half = recipe.precision == Precision::half_storage;
  // Every plane holds `stride` values, a multiple of the kernel's lanes; tiles are padded to it.
  const std::size_t stride =
      round_up(tile_pixels(compute_.device.info, recipe, pixels, max_tile_pixels), static_cast<std::size_t>(recipe.lanes));
  const std::size_t plane_bytes = stride * recipe.plane_count() * (half ? sizeof(cl_half) : sizeof(cl_float));
  if (!uniforms_ || uniforms_options_ != report.build_options || uniforms_stride_ != stride ||
      uniforms_rays_ != recipe.shadow_settings.rays || uniforms_environment_rays_ != recipe.environment_rays) {
    const auto upload_start = Clock::now();
    const ShadowCasters casters = shadow_casters(scene, recipe.shadow_settings);
    uniforms_ = upload_uniforms(context, pack_uniforms(scene, recipe), casters, stride);
    shadow_lights_ = table_buffer(context, casters.lights);
    shadow_light_count_ = casters.lights.size();
    uniforms_options_ = report.build_options;
    uniforms_stride_ = stride;
    uniforms_rays_ = recipe.shadow_settings.rays;
    uniforms_environment_rays_ = recipe.environment_rays;
    report.timings.upload_ms += milliseconds(upload_start, Clock::now());
  }
  prepare_shadows(scene, gbuffer, recipe, report);
  // One launch keeps its packed G-buffer for the next frame; tiles overwrite each other's.
  const PackedFor wanted{scene.camera.eye, recipe.precision, recipe.plane_count(), stride};
  const bool resident = stride >= pixels;
  if (!resident || (packed_ && packed_->key != wanted)) packed_.reset();
  // Culling lists are per light that casts shadows: none for an environment's rays alone.
  const bool shadows_culled = recipe.shadows != ShadowMode::off && recipe.shadow_casters > 0 && shadows_->device.culled;
  return FrameSetup{
      .stride = stride,
      .pack_target = {planes_.at_least(context, plane_bytes), material_index_.at_least(context, stride * sizeof(cl_int)),
                      stride, half_staging_},
      .output = output_.at_least(context, PHONGCL_OUTPUT_PLANES * stride * sizeof(cl_float)),
      .terms = terms_.at_least(context, (recipe.write_terms ? term_planes(recipe) * stride : 1) * sizeof(cl_float)),
      .tiles = light_list_layout(gbuffer.width, gbuffer.height, recipe.tile_size),
      .culler = recipe.tiled ? &culler_for(report.build_options) : nullptr,
      .shadow_tiles = tile_layout(gbuffer.width, gbuffer.height, kShadowCullingTile, kShadowCullingTile),
      .shadow_culler = shadows_culled ? &shadow_culler_for(report.build_options) : nullptr,
      .packed_for = wanted,
      .resident = resident};
}

std::size_t PhongShader::pack_or_reuse(const FrameSetup& frame, const Scene& scene, const GBuffer& gbuffer,
                                       const Recipe& recipe, std::size_t first, std::size_t count, std::size_t padded,
                                       ShadeReport& report) {
  if (packed_) {
    report.counts = packed_->counts;
    return packed_->flushed_to_zero;
  }
  const PackedTile packed =
      pack_into_mapped(compute_.queue, frame.pack_target, gbuffer, scene.camera.eye, recipe, first, count, padded);
  ++packings_;
  report.counts += packed.counts;
  report.timings.pack_ms += packed.pack_ms;
  report.timings.upload_ms += packed.upload_ms;
  report.timings.gbuffer_uploaded = true;
  if (frame.resident) packed_ = PackedFrame{frame.packed_for, packed.counts, packed.flushed_to_zero};
  return packed.flushed_to_zero;
}

cl::Event PhongShader::cull_and_launch(cl::Kernel& kernel, FrameSetup& frame, const Recipe& recipe, std::size_t first,
                                       std::size_t padded, ShadeReport& report) {
  const DeviceUniforms& uniforms = *uniforms_;
  frame.tiles.grid.first_pixel = static_cast<cl_uint>(first);
  frame.shadow_tiles.grid.first_pixel = static_cast<cl_uint>(first);
  const PackTarget& packed = frame.pack_target;
  TileCuller* culler = frame.culler;
  const ResidentShadows* shadows = recipe.shadows != ShadowMode::off ? &*shadows_ : nullptr;
  if (culler) {
    const CullingStats culled = culler->cull(packed.planes, frame.stride, packed.material_index, padded, frame.tiles,
                                             uniforms.point_bounds, uniforms.scalars.point_count, packings_);
    report.culling += culled;
    report.timings.kernel_ms += culled.culling_ms;
  }
  ShadowCuller* shadow_culler = frame.shadow_culler;
  if (shadow_culler) {
    const ShadowCullingStats culled = shadow_culler->cull(
        packed.planes, frame.stride, packed.material_index, padded, frame.shadow_tiles, shadows->device.geometry,
        shadow_lights_, shadow_light_count_, shadows->device.frame.offset_scale, shadows->device.frame.eye_extent,
        packings_);
    report.shadows_culled = true;
    report.shadow_culling += culled;
    report.timings.kernel_ms += culled.culling_ms;
  }
  const ShadowLists* lists = shadow_culler ? &shadow_culler->lists() : nullptr;
  FrameScalars scalars = uniforms.scalars;
  scalars.first_pixel = static_cast<cl_uint>(first);
  if (culler) {
    scalars.grid = frame.tiles.grid;
    scalars.tile_lists = culler->tables();
  }
  if (shadows) {
    scalars.shadow = shadows->device.frame;
    scalars.shadow_geometry = shadows->device.geometry.tables;
  }
  if (lists) {
    scalars.shadow_grid = frame.shadow_tiles.grid;
    scalars.shadow_tiles = lists->tiles;
    scalars.shadow_lists = lists->tables;
  }
  const PhongArguments arguments{.planes = packed.planes,
                                 .material_index = packed.material_index,
                                 .frame = scalars,
                                 .scene = uniforms.scene,
                                 .tile_lists = culler ? culler->block() : uniforms.no_tables,
                                 .shadow_geometry = shadows ? shadows->device.geometry.block : uniforms.no_tables,
                                 .shadow_lists = lists ? lists->block : uniforms.no_tables,
                                 .out_rgba = frame.output,
                                 .out_terms = frame.terms};
  return launch_phong(kernel, compute_, arguments, padded, recipe.lanes);
}

void PhongShader::download(const FrameSetup& frame, const GBuffer& gbuffer, const Recipe& recipe, std::size_t first,
                           std::size_t count, const FrameTargets& targets, ShadeReport& report) {
  cl::CommandQueue& queue = compute_.queue;
  cl::Event map_output;
  const auto* shaded = static_cast<const float*>(queue.enqueueMapBuffer(
      frame.output, CL_TRUE, CL_MAP_READ, 0, PHONGCL_OUTPUT_PLANES * frame.stride * sizeof(cl_float), nullptr, &map_output));
  const auto copy_start = Clock::now();
  interleave(shaded, frame.stride, count, PHONGCL_OUTPUT_PLANES, targets.rgba + 4 * first);
  premultiply_by_coverage(gbuffer.coverage, first, count, targets.rgba + 4 * first);
  const double copy_ms = milliseconds(copy_start, Clock::now());
  queue.enqueueUnmapMemObject(frame.output, const_cast<float*>(shaded));
  // The terms' and light groups' planes are mapped (blocking) and copied: wall clock.
  const auto terms_start = Clock::now();
  if (recipe.write_terms && targets.ambient)
    copy_terms(queue, frame.terms, frame.stride, first, count, gbuffer.coverage, targets);
  const double terms_ms = milliseconds(terms_start, Clock::now());
  queue.finish();
  report.timings.download_ms += event_milliseconds(map_output) + copy_ms + terms_ms;
}

ShadeReport PhongShader::shade_into(const Scene& scene, const GBuffer& gbuffer, const Recipe& recipe,
                                    const FrameTargets& targets, std::size_t max_tile_pixels) {
  ShadeReport report;
  describe_recipe(recipe, report);
  report.disk_cache_directory = cache_.disk_directory().string();
  report.disk_cache_problem = cache_.disk_problem();
  cl::Kernel& kernel = kernel_for(report);

  const auto start = Clock::now();
  FrameSetup frame = prepare(scene, gbuffer, recipe, max_tile_pixels, report);
  const std::size_t pixels = gbuffer.pixel_count();
  std::size_t flushed_to_zero = 0;
  for (std::size_t first = 0; first < pixels; first += frame.stride, ++report.tiles) {
    const std::size_t count = std::min(frame.stride, pixels - first);
    const std::size_t padded = round_up(count, static_cast<std::size_t>(recipe.lanes));
    flushed_to_zero += pack_or_reuse(frame, scene, gbuffer, recipe, first, count, padded, report);
    const cl::Event launched = cull_and_launch(kernel, frame, recipe, first, padded, report);
    download(frame, gbuffer, recipe, first, count, targets, report);
    report.timings.kernel_ms += event_milliseconds(launched);
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
