#pragma once
// From the host's G-buffer and scene to the kernel's device layout (kernels/layout.h).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gbuffer/gbuffer.h"
#include "scene/scene.h"
#include "shading/device_layout.h"
#include "shading/recipe.h"

namespace phongcl {

// Per-scene data every work-item reads.
struct UniformData {
  std::vector<PointLight> point_lights;
  std::vector<DirectionalLight> directional_lights;
  std::vector<MaterialRecord> materials;
  // Ambient, background, radiance scales and light counts; the shader sets plane_stride. Light and
  // ambient colours are divided by 2^e (exact), which the kernel undoes at the end.
  FrameScalars scalars{};
};
UniformData pack_uniforms(const Scene& scene);

// How many pixels fell in each class (the summary reports the non-finite ones).
struct PixelCounts {
  std::size_t shaded = 0, background = 0, nonfinite_position = 0, nonfinite_normal = 0, nonfinite_material = 0;
  void add(PixelClass pixel_class);
  PixelCounts& operator+=(const PixelCounts& other);
};

// Packs pixels [first, first + count) into float planes of `stride` values each (plane order in
// kernels/layout.h, then the recipe's per-pixel material planes) and the material index of each
// pixel (PHONGCL_BACKGROUND when not shaded); slots [count, padded_count) become background
// padding, so the kernel's SIMD lanes never read stale memory. Positions are stored relative to
// the eye, subtracted in double so that scenes far from the origin keep their precision.
PixelCounts pack_tile(const GBuffer& gbuffer, const glm::dvec3& eye, const Recipe& recipe, std::size_t first,
                      std::size_t count, std::size_t padded_count, std::size_t stride, float* planes,
                      std::int32_t* material_index);

// Converts packed float planes to half for the half-storage variant. Normals are first scaled by
// their largest component so that no length overflows half. Throws InputError (naming the
// G-buffer, plane and pixel) when a value is beyond half's range; returns how many non-zero values
// were too small for half and became zero.
std::size_t convert_planes_to_half(const GBuffer& gbuffer, const Recipe& recipe, std::size_t first, std::size_t count,
                                   std::size_t stride, float* planes, std::uint16_t* half_planes);

}  // namespace phongcl
