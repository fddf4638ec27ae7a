#pragma once
// From the host's G-buffer and scene to the kernel's device layout (kernels/layout.h).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gbuffer/gbuffer.h"
#include "scene/scene.h"
#include "shading/device_layout.h"
#include "shading/pack_environment.h"
#include "shading/recipe.h"
#include "shading/shade_stats.h"  // PixelCounts

namespace phongcl {

// Per-scene data every work-item reads.
struct UniformData {
  std::vector<PointLight> point_lights;     // point and spot lights, in scene order
  std::vector<LightShape> point_shapes;     // parallel to point_lights
  std::vector<LightBounds> point_bounds;    // parallel to point_lights: what each can reach, for culling
  std::vector<LinkWord> links;              // recipe.link_words per light: point lights, then directional
  std::vector<DirectionalLight> directional_lights;
  std::vector<MaterialRecord> materials;
  // With LIGHT_GROUPS: each light's group (point lights, then directional, then area lights), its index in
  // recipe.light_groups or their count for none.
  std::vector<layout_uint> light_groups;
  std::vector<AreaLightRecord> area_lights;  // shading/pack_area.h
  PackedEnvironment environment;             // shading/pack_environment.h
  // Ambient, background, radiance scales and light counts; the shader sets plane_stride. Light and
  // ambient colours are divided by 2^e (exact), which the kernel undoes at the end.
  FrameScalars scalars{};
};
UniformData pack_uniforms(const Scene& scene, const Recipe& recipe);

// A point or spot light's falloff power, 1/range and cone (kernels/layout.h says how points and
// hard edges are encoded).
LightShape light_shape(const Light& light);

// What a point or spot light can reach, as a sphere relative to the eye: its range, or the smaller
// sphere around a spot's cone cut by it; radius -1 without a range. Widened by 1e-5 of the scale
// against the float rounding of the kernel's distances: culling must never drop a light that adds.
LightBounds light_bounds(const Light& light, const glm::dvec3& eye);

// Packs pixels [first, first + count) into float planes of `stride` values each (plane order in
// kernels/layout.h, then the recipe's per-pixel material planes) and the material index of each
// pixel (PHONGCL_BACKGROUND when not shaded); slots [count, padded_count) become background
// padding, so the kernel's SIMD lanes never read stale memory. Positions are stored relative to
// the eye, subtracted in double so that scenes far from the origin keep their precision; with
// recipe.position_rest also what their float rounding lost, in three planes after the others.
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
