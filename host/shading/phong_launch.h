#pragma once
// The pieces of a Phong frame on the device that the one-shot shader (phong_shader.h) and the
// resident relighter (include/phongcl/relighter.hpp) share: tile sizes, the scene's tables on the
// device, the typed kernel launch, and copying the output planes out.
#include <cstddef>

#include "cl/device_info.h"
#include "cl/opencl.h"
#include "shading/pack.h"
#include "shading/recipe.h"

namespace phongcl {

// Pixels per tile: the whole frame unless a buffer would exceed the device's largest allocation or
// the tile's buffers its memory. `limit` > 0 caps it.
std::size_t tile_pixels(const DeviceInfo& device, const Recipe& recipe, std::size_t pixels, std::size_t limit);

inline std::size_t round_up(std::size_t value, std::size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

// The light and material tables in device memory, with the per-frame scalars they go with.
struct DeviceUniforms {
  cl::Buffer materials, point_lights, directional_lights;
  FrameScalars scalars{};
};
// `plane_stride`: values per plane of the tile the kernel will shade.
DeviceUniforms upload_uniforms(const cl::Context& context, const UniformData& uniforms, std::size_t plane_stride);

// The tile's buffers, in kernels/layout.h's plane order.
struct TileBuffers {
  const cl::Buffer& planes;          // G-buffer planes (float, or half with half-storage)
  const cl::Buffer& material_index;  // one int per slot, PHONGCL_BACKGROUND where not shaded
  const cl::Buffer& output;          // PHONGCL_OUTPUT_PLANES planes
  const cl::Buffer& terms;           // PHONGCL_TERM_PLANES planes with WRITE_TERMS, else unused
};

// phong.cl's phong_shade in `program`. Setting a kernel's arguments is not thread-safe: one kernel
// object per thread that launches.
cl::Kernel phong_kernel(const cl::Program& program);
// Enqueues phong_shade over `slots` pixels (a multiple of the recipe's lanes).
cl::Event launch_phong(const cl::Kernel& kernel, cl::CommandQueue& queue, const TileBuffers& tile,
                       const DeviceUniforms& uniforms, std::size_t slots, int lanes);

// Interleaves the first `channels` of count pixels' planes (stride values each) into RGBA pixels,
// on every core: the copy is part of each frame's end-to-end time.
void interleave(const float* planes, std::size_t stride, std::size_t count, int channels, float* rgba);

// The edge policy (gbuffer/edge_policy.h), after the kernel: a shaded pixel (alpha 1) of a frame
// with coverage gets colour and alpha times its coverage, premultiplied for compositing. Pixels
// [first, first + count) of the frame, whose RGBA starts at rgba.
void premultiply_by_coverage(const Plane& coverage, std::size_t first, std::size_t count, float* rgba);

}  // namespace phongcl
