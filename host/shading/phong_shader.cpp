#include "shading/phong_shader.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "cl/kernel_source.h"
#include "shading/phong_launch.h"

namespace phongcl {

namespace {

using Clock = std::chrono::steady_clock;

double milliseconds(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double, std::milli>(end - start).count();
}

// Copies the kernel's term planes into the three term images, alpha from the combined image
// (premultiplied like it, so the terms still sum to it).
void copy_terms(cl::CommandQueue& queue, const cl::Buffer& terms, std::size_t stride, std::size_t first,
                std::size_t count, const Plane& coverage, ShadeResult& result) {
  const auto* planes = static_cast<const float*>(
      queue.enqueueMapBuffer(terms, CL_TRUE, CL_MAP_READ, 0, PHONGCL_TERM_PLANES * stride * sizeof(cl_float)));
  Image* images[] = {&result.terms.ambient, &result.terms.diffuse, &result.terms.specular};
  for (int term = 0; term < 3; ++term) {
    float* out = images[term]->pixel(first);
    interleave(planes + 3 * term * stride, stride, count, 3, out);
    for (std::size_t t = 0; t < count; ++t) {
      out[4 * t + 3] = result.image.pixel(first + t)[3];
      if (!coverage.empty() && out[4 * t + 3] > 0.0f)
        for (int c = 0; c < 3; ++c) out[4 * t + c] *= coverage[first + t];
    }
  }
  queue.enqueueUnmapMemObject(terms, const_cast<float*>(planes));
}

}  // namespace

ShadeResult PhongShader::shade(const Scene& scene, const GBuffer& gbuffer, const ShadeOptions& options) {
  check_materials(gbuffer, scene.materials.size());
  ShadeResult result;
  result.recipe = make_recipe(scene, gbuffer, compute_.device.info, options);
  const Recipe& recipe = result.recipe;
  result.build_options = recipe.build_options();
  const BuiltProgram built = cache_.build(compute_, load_kernel_source("phong.cl"), result.build_options);
  result.cache = built.outcome;
  result.timings.build_ms = built.build_milliseconds;
  const cl::Kernel kernel = phong_kernel(built.program);

  const auto start = Clock::now();
  const cl::Context& context = compute_.context;
  cl::CommandQueue& queue = compute_.queue;

  const std::size_t pixels = gbuffer.pixel_count();
  const bool half = recipe.precision == Precision::half_storage;
  const std::size_t lanes = static_cast<std::size_t>(recipe.lanes);
  // Every plane holds `stride` values, a multiple of the kernel's lanes; tiles are padded to it.
  const std::size_t stride = round_up(tile_pixels(compute_.device.info, recipe, pixels, options.max_tile_pixels), lanes);
  const std::size_t plane_bytes = stride * recipe.plane_count() * (half ? sizeof(cl_half) : sizeof(cl_float));
  const cl::Buffer& planes = planes_.at_least(context, plane_bytes);
  const cl::Buffer& material_index = material_index_.at_least(context, stride * sizeof(cl_int));
  const cl::Buffer& output = output_.at_least(context, PHONGCL_OUTPUT_PLANES * stride * sizeof(cl_float));
  const cl::Buffer& terms =
      terms_.at_least(context, (recipe.write_terms ? PHONGCL_TERM_PLANES * stride : 1) * sizeof(cl_float));
  const DeviceUniforms uniforms = upload_uniforms(context, pack_uniforms(scene), stride);
  std::vector<float> half_staging(half ? stride * recipe.plane_count() : 0);
  std::size_t flushed_to_zero = 0;

  result.image = image_like(gbuffer);
  if (recipe.write_terms) {
    result.terms = {image_like(gbuffer), image_like(gbuffer), image_like(gbuffer)};
  }
  for (std::size_t first = 0; first < pixels; first += stride, ++result.tiles) {
    const std::size_t count = std::min(stride, pixels - first);
    const std::size_t padded = round_up(count, lanes);
    const auto pack_start = Clock::now();
    void* mapped_planes = queue.enqueueMapBuffer(planes, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, plane_bytes);
    auto* mapped_index = static_cast<cl_int*>(
        queue.enqueueMapBuffer(material_index, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, stride * sizeof(cl_int)));
    float* float_planes = half ? half_staging.data() : static_cast<float*>(mapped_planes);
    try {
      result.counts += pack_tile(gbuffer, scene.camera.eye, recipe, first, count, padded, stride, float_planes, mapped_index);
      if (half) {
        flushed_to_zero += convert_planes_to_half(gbuffer, recipe, first, padded, stride, float_planes,
                                                  static_cast<std::uint16_t*>(mapped_planes));
      }
    } catch (...) {
      // The buffers outlive this frame: leave them unmapped (a value beyond half's range throws).
      queue.enqueueUnmapMemObject(planes, mapped_planes);
      queue.enqueueUnmapMemObject(material_index, mapped_index);
      queue.finish();
      throw;
    }
    result.timings.pack_ms += milliseconds(pack_start, Clock::now());

    cl::Event unmap_planes, unmap_index;
    queue.enqueueUnmapMemObject(planes, mapped_planes, nullptr, &unmap_planes);
    queue.enqueueUnmapMemObject(material_index, mapped_index, nullptr, &unmap_index);
    const cl::Event launched =
        launch_phong(kernel, queue, {planes, material_index, output, terms}, uniforms, padded, recipe.lanes);

    cl::Event map_output;
    const auto* shaded = static_cast<const float*>(
        queue.enqueueMapBuffer(output, CL_TRUE, CL_MAP_READ, 0, PHONGCL_OUTPUT_PLANES * stride * sizeof(cl_float), nullptr, &map_output));
    const auto copy_start = Clock::now();
    interleave(shaded, stride, count, 4, result.image.pixel(first));
    premultiply_by_coverage(gbuffer.coverage, first, count, result.image.pixel(first));
    const double copy_ms = milliseconds(copy_start, Clock::now());
    queue.enqueueUnmapMemObject(output, const_cast<float*>(shaded));
    if (recipe.write_terms) copy_terms(queue, terms, stride, first, count, gbuffer.coverage, result);
    queue.finish();

    result.timings.upload_ms += event_milliseconds(unmap_planes) + event_milliseconds(unmap_index);
    result.timings.kernel_ms += event_milliseconds(launched);
    result.timings.download_ms += event_milliseconds(map_output) + copy_ms;
  }
  result.timings.total_ms = milliseconds(start, Clock::now());
  if (flushed_to_zero > 0) {
    result.warnings.push_back(std::to_string(flushed_to_zero) +
                              " non-zero G-buffer values were below half's smallest subnormal (6e-8) and became 0 "
                              "in --precision half-storage");
  }
  return result;
}

}  // namespace phongcl
