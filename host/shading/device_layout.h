#pragma once
// kernels/layout.h seen from the host, with its sizes and offsets checked at compile time: a
// mismatch with the kernel's view would shade silently wrong, so it must not build.
#include <cstddef>

extern "C" {
#include "kernels/layout.h"
}

static_assert(sizeof(layout_float) == 4 && sizeof(layout_int) == 4 && sizeof(layout_uint) == 4);
static_assert(offsetof(FrameScalars, background) == 16 && offsetof(FrameScalars, radiance_scale_a) == 32 &&
              offsetof(FrameScalars, point_count) == 40 && offsetof(FrameScalars, plane_stride) == 48 &&
              offsetof(FrameScalars, shadow_tiles) == 56 && offsetof(FrameScalars, scene) == 64 &&
              offsetof(FrameScalars, tile_lists) == 116 && offsetof(FrameScalars, shadow_geometry) == 132 &&
              offsetof(FrameScalars, shadow_lists) == 152 && offsetof(FrameScalars, grid) == 164 &&
              offsetof(FrameScalars, shadow_grid) == 184 && offsetof(FrameScalars, shadow) == 204 &&
              offsetof(FrameScalars, first_pixel) == 60 && sizeof(FrameScalars) == 204 + sizeof(ShadowFrame));
static_assert(sizeof(EnvironmentRecord) == 80 && offsetof(EnvironmentRecord, scale) == 48 &&
              offsetof(EnvironmentRecord, rays) == 60 && offsetof(EnvironmentRecord, sun_count) == 64 &&
              offsetof(EnvironmentRecord, sky_offset) == 76);
static_assert(sizeof(EnvironmentSun) == 32 && offsetof(EnvironmentSun, color) == 16);
static_assert(sizeof(EnvironmentLobe) == 32 && offsetof(EnvironmentLobe, amplitude) == 12 &&
              offsetof(EnvironmentLobe, split_sum) == 20 && offsetof(EnvironmentLobe, spread) == 24 &&
              offsetof(EnvironmentLobe, half_vector) == 28);
static_assert(sizeof(SceneTables) == 52 && sizeof(TileListTables) == 16 && sizeof(ShadowGeometryTables) == 20 &&
              sizeof(ShadowListTables) == 12);
static_assert(PHONGCL_UNROLL_LIGHT_LIMIT <= PHONGCL_LIGHT_BLOCK, "an unrolled light loop is one compensated block");
static_assert(sizeof(PointLight) == 48 && offsetof(PointLight, color) == 16 && offsetof(PointLight, position_rest) == 32);
static_assert(sizeof(DirectionalLight) == 32 && offsetof(DirectionalLight, color) == 16);
static_assert(sizeof(MaterialRecord) == 112 && sizeof(SoftLight) == 8);
static_assert(offsetof(FrameScalars, area_count) == 52);
static_assert(sizeof(AreaLightRecord) == 96 && offsetof(AreaLightRecord, color) == 64 && offsetof(AreaLightRecord, shape) == 80);
static_assert(offsetof(MaterialRecord, ka) == MATERIAL_KA * sizeof(float) &&
              offsetof(MaterialRecord, kd) == MATERIAL_KD * sizeof(float) &&
              offsetof(MaterialRecord, ks) == MATERIAL_KS * sizeof(float) &&
              offsetof(MaterialRecord, shininess) == MATERIAL_SHININESS * sizeof(float) &&
              offsetof(MaterialRecord, specular_model) == MATERIAL_SPECULAR_MODEL * sizeof(float) &&
              offsetof(MaterialRecord, roughness) == MATERIAL_ROUGHNESS * sizeof(float) &&
              offsetof(MaterialRecord, ior) == MATERIAL_IOR * sizeof(float) &&
              offsetof(MaterialRecord, metal_f0) == MATERIAL_METAL_F0 * sizeof(float) &&
              offsetof(MaterialRecord, metal_f0[3]) == MATERIAL_METALLIC * sizeof(float) &&
              offsetof(MaterialRecord, metal_b) == MATERIAL_METAL_B * sizeof(float) &&
              offsetof(MaterialRecord, metal_b[3]) == MATERIAL_DIELECTRIC_LAYER * sizeof(float) &&
              offsetof(MaterialRecord, fresnel_average) == MATERIAL_FRESNEL_AVERAGE * sizeof(float) &&
              offsetof(MaterialRecord, diffuse_roughness) == MATERIAL_DIFFUSE_ROUGHNESS * sizeof(float));
static_assert(sizeof(LightShape) == 48 && offsetof(LightShape, inverse_range) == 16 && offsetof(LightShape, falloff) == 32 &&
              offsetof(LightShape, cosine_power) == 36);
static_assert(sizeof(LightBounds) == 64 && offsetof(LightBounds, apex) == 16 && offsetof(LightBounds, distance_bins) == 48 &&
              sizeof(TileGrid) == 20 && sizeof(LinkWord) == 4);
static_assert(sizeof(TileBox) == 32 && offsetof(TileBox, hi) == 16);

namespace phongcl {

// The scene block's tables (SceneTables) start at multiples of a cache line: no table shares one with
// the next, and nothing takes them as sub-buffers, which would need the device's alignment.
constexpr std::size_t kSceneTableAlignment = 64;
constexpr std::size_t kSceneTables = sizeof(SceneTables) / sizeof(layout_uint);

}  // namespace phongcl
