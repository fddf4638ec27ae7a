#pragma once
// The pieces of a Phong frame on the device, which the shader (phong_shader.h) puts together: tile
// sizes, packing into device memory, the scene's tables on the device, the launch with named
// arguments, and copying the output planes out.
#include <cstddef>
#include <vector>

#include "cl/compute_context.h"
#include "cl/device_info.h"
#include "cl/opencl.h"
#include "shading/pack.h"
#include "shading/phong_arguments.h"
#include "shading/recipe.h"
#include "shading/shadow_inputs.h"

namespace phongcl {

// Pixels per tile: the whole frame unless a buffer would exceed the device's largest allocation or
// the tile's buffers its memory. `limit` > 0 caps it.
std::size_t tile_pixels(const DeviceInfo& device, const Recipe& recipe, std::size_t pixels, std::size_t limit);

inline std::size_t round_up(std::size_t value, std::size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

// Where a tile's G-buffer goes: ALLOC_HOST_PTR buffers, mapped for writing so that on a CPU device
// packing writes straight into device memory.
struct PackTarget {
  const cl::Buffer& planes;          // recipe.plane_count() planes of `stride` values (half with half-storage)
  const cl::Buffer& material_index;  // `stride` ints
  std::size_t stride = 0;
  // half-storage: the float planes before their conversion, kept from frame to frame (a fresh
  // vector, 58 MB at 1080p, was zeroed and paged in every frame: 110 ms).
  std::vector<float>& half_staging;
};
struct PackedTile {
  PixelCounts counts;
  std::size_t flushed_to_zero = 0;  // half-storage: non-zero values too small for half
  double pack_ms = 0.0;             // host packing; upload_ms: the unmaps (profiling events)
  double upload_ms = 0.0;
};
// Packs pixels [first, first + count) into the mapped buffers (pack_tile, then half conversion),
// padded to `padded` slots, and unmaps them, on an exception too: they outlive the frame.
PackedTile pack_into_mapped(cl::CommandQueue& queue, const PackTarget& target, const GBuffer& gbuffer,
                            const glm::dvec3& eye, const Recipe& recipe, std::size_t first, std::size_t count,
                            std::size_t padded);

// The scene's tables in device memory, in one block (kernels/layout.h's SceneTables), with the
// per-frame scalars they go with.
struct DeviceUniforms {
  cl::Buffer scene;         // materials, lights, shapes, links, area lights, shadow casters, light groups
  cl::Buffer point_bounds;  // what each point light reaches, for culling (parallel to the point lights)
  cl::Buffer no_tables;     // stands in for a block the frame does not make (tile or shadow lists, geometry)
  FrameScalars scalars{};   // with scalars.scene saying where each table starts
};
// `shadow_casters`: the lights' shadow words and area lights' rays (shading/shadow_inputs.h);
// `plane_stride`: values per plane of the tile the kernel will shade.
DeviceUniforms upload_uniforms(const cl::Context& context, const UniformData& uniforms,
                               const ShadowCasters& shadow_casters, std::size_t plane_stride);

// phong.cl's phong_shade in `program`.
cl::Kernel phong_kernel(const cl::Program& program);
// Sets the kernel's arguments and enqueues it over `slots` pixels (a multiple of the recipe's lanes).
// Setting a kernel's arguments is not thread-safe: one kernel object per thread that launches.
cl::Event launch_phong(cl::Kernel& kernel, const ComputeContext& compute, const PhongArguments& arguments,
                       std::size_t slots, int lanes);

// Interleaves the first `channels` of count pixels' planes (stride values each) into RGBA pixels,
// on every core: the copy is part of each frame's end-to-end time.
void interleave(const float* planes, std::size_t stride, std::size_t count, int channels, float* rgba);

// The edge policy (gbuffer/edge_policy.h), after the kernel: a shaded pixel (alpha 1) of a frame
// with coverage gets colour and alpha times its coverage, premultiplied for compositing. Pixels
// [first, first + count) of the frame, whose RGBA starts at rgba.
void premultiply_by_coverage(const Plane& coverage, std::size_t first, std::size_t count, float* rgba);

}  // namespace phongcl
