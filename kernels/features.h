/* The flags phong.cl is built with. The host's recipe (host/shading/recipe.cpp) defines every one of
 * them, from one table that `phongcl shade --explain` prints with a reason for each; the code tests
 * them with `if (FLAG)`, so every variant parses and the compiler folds away what a scene does not use.
 *   PHONGCL_LANES=n                        pixels per work-item: 1, 2, 4, 8 or 16 (phong_math.h)
 *   PHONGCL_DOUBLE, PHONGCL_FAST           fp64 arithmetic; built with -cl-fast-relaxed-math
 *   HALF_STORAGE                           G-buffer planes stored as half (storage.h)
 *   UNIFORM_SPACE=__constant|__global      where the light and material tables live
 *   POINT_LIGHTS, DIRECTIONAL_LIGHTS       light types present
 *   POINT_COUNT=n, DIRECTIONAL_COUNT=n     light counts in the code (loops unroll); 0: read at run time
 *   SPECULAR, AMBIENT                      terms present
 *   SPECULAR_MODELS=m                      the specular models the materials use, a mask of bit 1 << model
 *                                          (specular.h); 1: Phong's alone, the default lobe; 16, 32:
 *                                          Cycles' Principled BSDF v1, v2 (principled.h)
 *   OREN_NAYAR                             a Principled v2 material has a Diffuse Roughness (oren_nayar.h)
 *   SINGLE_MATERIAL                        every shaded pixel uses materials[0]: no per-pixel fetch
 *   MATERIAL_COUNT=n                       a table of n <= PHONGCL_LANES materials: selects, no gather;
 *                                          0: gathered per lane
 *   PER_PIXEL_KA, _KD, _KS, _Q             the G-buffer has per-pixel material planes (material.h)
 *   POSITION_REST                          positions and point lights come as float pairs, value + rest:
 *                                          L - P to float precision however near the light (phong.cl)
 *   FALLOFF=k, FALLOFF_MIXED               every light falls off as 1/d^k; powers differ (light_shape.h)
 *   RANGE_WINDOW, SPOT_LIGHTS              some light has a range; some light is a spot
 *   SPOT_COSINE_POWER                      some spot has a cosine power p > 0: F gains max(0, c)^p
 *   LIGHT_LINKING=w                        w mask words per light; 0: every light lights every material
 *   TILED_CULLING                          point and spot lights from the work-item's tile list (cull.cl)
 *   WRITE_TERMS                            also write ambient, diffuse, specular apart (AOVs)
 *   LIGHT_GROUPS=g                         with WRITE_TERMS: g light groups, each one's diffuse + specular
 *                                          also written apart after the terms; 0: no groups
 *   AREA_LIGHTS                            some light is a rect or disk emitter (area_light.h)
 *   SHADOWS, SCREEN_SHADOWS                some light casts shadows: traced against the scene's geometry,
 *                                          or marched across the frame's depth plane (shadow.h)
 *   ENVIRONMENT                            the scene has an environment light (environment.h)
 *   ENVIRONMENT_SHADOWS                    its visibility rays are traced (with SHADOWS; SCREEN_SHADOWS marches them)
 *   SOFT_SHADOWS                           some area light's shadow is traced with several rays over the
 *                                          emitter, weighted by the visible fraction (soft_shadow.h)
 */
#ifndef PHONGCL_FEATURES_H
#define PHONGCL_FEATURES_H

#if !defined(PHONGCL_LANES) || !defined(PHONGCL_DOUBLE) || !defined(PHONGCL_FAST) || !defined(HALF_STORAGE) ||  \
    !defined(UNIFORM_SPACE) || !defined(POINT_LIGHTS) || !defined(DIRECTIONAL_LIGHTS) || !defined(POINT_COUNT) || \
    !defined(DIRECTIONAL_COUNT) || !defined(SPECULAR) || !defined(AMBIENT) || !defined(SINGLE_MATERIAL) ||         \
    !defined(MATERIAL_COUNT) || !defined(PER_PIXEL_KA) || !defined(PER_PIXEL_KD) || !defined(PER_PIXEL_KS) ||     \
    !defined(PER_PIXEL_Q) || !defined(FALLOFF) || !defined(FALLOFF_MIXED) || !defined(RANGE_WINDOW) ||            \
    !defined(SPOT_LIGHTS) || !defined(SPOT_COSINE_POWER) || !defined(LIGHT_LINKING) || !defined(TILED_CULLING) ||   \
    !defined(WRITE_TERMS) || !defined(SHADOWS) || !defined(SCREEN_SHADOWS) || !defined(POSITION_REST) ||          \
    !defined(LIGHT_GROUPS) || !defined(SPECULAR_MODELS) || !defined(AREA_LIGHTS) || !defined(SOFT_SHADOWS) ||   \
    !defined(ENVIRONMENT) || !defined(ENVIRONMENT_SHADOWS) || !defined(OREN_NAYAR)
#error "phong.cl is built with every flag of features.h defined (host/shading/recipe.cpp writes them)"
#endif

/* 1/d^k can exceed float near a light: the sums then guard 0 * Inf (NONNEGATIVE_TIMES, kahan_add). */
#define WEIGHT_CAN_OVERFLOW (FALLOFF > 0 || FALLOFF_MIXED)
/* The light's distance d, not only the direction to it. */
#define NEEDS_DISTANCE (WEIGHT_CAN_OVERFLOW || RANGE_WINDOW)
/* Point lights read their LightShape. */
#define POINT_SHAPES (NEEDS_DISTANCE || SPOT_LIGHTS)
/* The specular models present (specular.h numbers them): lobes around the reflection vector (Phong)
 * or the half vector (Blinn), normalised ones, and whether lanes may differ in their model. */
#define REFLECTION_LOBES ((SPECULAR_MODELS & 3) != 0)
#define HALF_VECTOR_LOBES ((SPECULAR_MODELS & 12) != 0)
#define NORMALIZED_LOBES ((SPECULAR_MODELS & 10) != 0)
#define MIXED_SPECULAR_MODELS ((SPECULAR_MODELS & (SPECULAR_MODELS - 1)) != 0)
/* Cycles' Principled BSDF (principled.h), models 4 (v1) and 5 (v2): in some lanes, or in every one. */
#define PRINCIPLED_LOBES ((SPECULAR_MODELS & 48) != 0)
#define ONLY_PRINCIPLED_LOBES ((SPECULAR_MODELS & ~48) == 0)
#define PRINCIPLED_V1 ((SPECULAR_MODELS & 16) != 0)
#define PRINCIPLED_V2 ((SPECULAR_MODELS & 32) != 0)
#define ONLY_PRINCIPLED_V2 (SPECULAR_MODELS == 32)

#endif
