#include "shading/phong_launch.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "cl/compute_context.h"
#include "cl/table_block.h"
#include "cl/work_groups.h"
#include "common/host_threads.h"

namespace phongcl {

namespace {

// OpenCL has no empty buffers: an unused table still gets one zeroed element.
template <typename T>
cl::Buffer uniform_buffer(const cl::Context& context, std::vector<T> values) {
  if (values.empty()) values.resize(1);
  return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, values.size() * sizeof(T), values.data());
}

}  // namespace

PackedTile pack_into_mapped(cl::CommandQueue& queue, const PackTarget& target, const GBuffer& gbuffer,
                            const glm::dvec3& eye, const Recipe& recipe, std::size_t first, std::size_t count,
                            std::size_t padded) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const bool half = recipe.precision == Precision::half_storage;
  const std::size_t stride = target.stride;
  const std::size_t plane_bytes = stride * recipe.plane_count() * (half ? sizeof(cl_half) : sizeof(cl_float));
  void* mapped_planes = queue.enqueueMapBuffer(target.planes, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, plane_bytes);
  auto* mapped_index = static_cast<cl_int*>(queue.enqueueMapBuffer(
      target.material_index, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, stride * sizeof(cl_int)));
  if (half) target.half_staging.resize(stride * recipe.plane_count());
  float* float_planes = half ? target.half_staging.data() : static_cast<float*>(mapped_planes);
  PackedTile packed;
  try {
    packed.counts = pack_tile(gbuffer, eye, recipe, first, count, padded, stride, float_planes, mapped_index);
    if (half)
      packed.flushed_to_zero = convert_planes_to_half(gbuffer, recipe, first, padded, stride, float_planes,
                                                      static_cast<std::uint16_t*>(mapped_planes));
  } catch (...) {
    // A value beyond half's range throws: leave the buffers unmapped for the next frame.
    queue.enqueueUnmapMemObject(target.planes, mapped_planes);
    queue.enqueueUnmapMemObject(target.material_index, mapped_index);
    queue.finish();
    throw;
  }
  packed.pack_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  cl::Event unmap_planes, unmap_index;
  queue.enqueueUnmapMemObject(target.planes, mapped_planes, nullptr, &unmap_planes);
  queue.enqueueUnmapMemObject(target.material_index, mapped_index, nullptr, &unmap_index);
  queue.finish();
  packed.upload_ms = event_milliseconds(unmap_planes) + event_milliseconds(unmap_index);
  return packed;
}

std::size_t tile_pixels(const DeviceInfo& device, const Recipe& recipe, std::size_t pixels, std::size_t limit) {
  const std::size_t plane_bytes = recipe.precision == Precision::half_storage ? 2 : 4;
  const std::size_t largest_per_pixel =
      std::max<std::size_t>(recipe.plane_count() * plane_bytes, PHONGCL_OUTPUT_PLANES * sizeof(float));
  const std::size_t total_per_pixel =
      recipe.plane_count() * plane_bytes + sizeof(cl_int) + PHONGCL_OUTPUT_PLANES * sizeof(float);
  std::size_t tile = std::min<std::size_t>(pixels, device.max_allocation / largest_per_pixel);
  tile = std::min<std::size_t>(tile, device.global_memory / 2 / total_per_pixel);
  if (limit > 0) tile = std::min(tile, limit);
  return std::max<std::size_t>(tile, 1);
}

DeviceUniforms upload_uniforms(const cl::Context& context, const UniformData& uniforms,
                               const ShadowCasters& shadow_casters, std::size_t plane_stride) {
  TableBlockLayout block(kSceneTableAlignment);
  FrameScalars scalars = uniforms.scalars;
  scalars.scene = {.materials = block.add(uniforms.materials),
                   .point_lights = block.add(uniforms.point_lights),
                   .point_shapes = block.add(uniforms.point_shapes),
                   .links = block.add(uniforms.links),
                   .directional_lights = block.add(uniforms.directional_lights),
                   .area_lights = block.add(uniforms.area_lights),
                   .shadow_casters = block.add(shadow_casters.words),
                   .light_groups = block.add(uniforms.light_groups),
                   .soft_lights = block.add(shadow_casters.soft),
                   .environment = block.add(uniforms.environment.record),
                   .environment_texels = block.add(uniforms.environment.texels),
                   .environment_suns = block.add(uniforms.environment.suns),
                   .environment_lobes = block.add(uniforms.environment.lobes)};
  scalars.plane_stride = static_cast<layout_uint>(plane_stride);
  return DeviceUniforms{.scene = block.upload(context, CL_MEM_READ_ONLY),
                        .point_bounds = uniform_buffer(context, uniforms.point_bounds),
                        .no_tables = uniform_buffer(context, std::vector<cl_uint>{}),
                        .scalars = scalars};
}

std::vector<std::string> phong_argument_names() {
  std::vector<std::string> names;
  PhongArguments unset;
  for_each_argument(unset, [&names](const char* name, const auto&) { names.push_back(name); });
  return names;
}

void set_arguments(cl::Kernel& kernel, const PhongArguments& arguments) {
  cl_uint index = 0;
  for_each_argument(arguments, [&](const char*, const auto& value) { kernel.setArg(index++, value); });
}

cl::Kernel phong_kernel(const cl::Program& program) { return cl::Kernel(program, "phong_shade"); }

cl::Event launch_phong(cl::Kernel& kernel, const ComputeContext& compute, const PhongArguments& arguments,
                       std::size_t slots, int lanes) {
  set_arguments(kernel, arguments);
  const std::size_t items = slots / static_cast<std::size_t>(lanes);
  // Up to 64 work-items per group, against PoCL's default of 3,600 at 1080p: the frame took 0.85 of
  // its time at 10,000 lights, 0.92 at 64 and 0.93 at 256 unculled (paired, alternated).
  cl::Event launched;
  compute.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items),
                                     spread_work_groups(compute.device.info, items, 64), nullptr, &launched);
  return launched;
}

void interleave(const float* planes, std::size_t stride, std::size_t count, int channels, float* rgba) {
  for_each_core_range(count, 1 << 12, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      for (int c = 0; c < channels; ++c) rgba[4 * t + c] = planes[c * stride + t];
    }
  });
}

void premultiply_by_coverage(const Plane& coverage, std::size_t first, std::size_t count, float* rgba) {
  if (coverage.empty()) return;
  for (std::size_t t = 0; t < count; ++t) {
    if (rgba[4 * t + 3] != 1.0f) continue;
    for (int c = 0; c < 4; ++c) rgba[4 * t + c] *= coverage[first + t];
  }
}

}  // namespace phongcl
