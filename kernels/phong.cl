/* Deferred Phong shading. Each work-item shades PHONGCL_LANES consecutive pixels as OpenCL vectors
 * (phong_math.h):
 *   L_o = ka*La + sum_i Li F_i [ kd*max(0, n.l_i) + ks*max(0, v.r_i)^q ],  r = 2(n.l)n - l
 * with Phong's lobe, or the one the material's specular model chooses (specular.h). shade_pixel()
 * is that formula's three terms; light_contribution() what one light adds (n.l, v.r, the power q);
 * add_point_light() and add_directional_light() each light's l and F_i (falloff, range, cone,
 * linking: light_shape.h); sum_light_kind() the loop that visits the lights (blocks, compensated
 * sums, pending powers, culled lists). The tuned arithmetic (robust normalisation, the power,
 * compensated sums, streaming stores) is phong_math.h's.
 * With AREA_LIGHTS rects and disks add theirs too (area_light.h: the diffuse term exact, the
 * specular one by quadrature), looped over untiled; their shadows are one ray to the centre, or
 * with SOFT_SHADOWS the visible fraction of the emitter from several (soft_shadow.h).
 * With ENVIRONMENT the world's light adds its irradiance from a precomputed map to the diffuse sum,
 * with ENVIRONMENT_SHADOWS less the sky its blocked visibility rays point at (environment.h), or with
 * SCREEN_SHADOWS the sky below the depth plane's horizons (environment_horizons.h).
 * With SHADOWS a light that casts shadows is multiplied by its visibility (shadow.h: a ray traced
 * against the scene's geometry, or with SCREEN_SHADOWS marched across the frame's depth plane).
 * With LIGHT_GROUPS the lights are summed group by group, and each group's terms also written apart.
 * Only what the scene needs is compiled in: the host's recipe defines every flag of features.h.
 * Every buffer is planar with frame.plane_stride values per plane, a multiple of PHONGCL_LANES (the
 * host pads each tile with background pixels). The tables come in a few blocks, one buffer each,
 * FrameScalars saying where each table starts (layout.h; docs/kernel.md).
 */
#include "area_light.h"
#include "environment.h"
#include "environment_horizons.h"
#include "environment_specular.h"
#include "features.h"
#include "layout.h"
#include "light_shape.h"
#include "material.h"
#include "phong_math.h"
#include "shadow.h"
#include "soft_shadow.h"
#include "principled.h"
#include "area_ltc.h"
#include "specular.h"
#include "storage.h"
#include "tiles.h"

/* A vector of pixels as the lights see it. The eye is the origin. */
typedef struct {
  vec3 p;          /* position */
  vec3 p_rest;     /* with POSITION_REST, what p's float rounding lost (p + p_rest is the host's double) */
  vec3 n, v;       /* unit normal; unit vector to the eye, normalize(-p) (zero where degenerate) */
  realv shininess; /* q */
  realv highlight_cutoff; /* with SPECULAR, highlight_cutoff(q) */
  realv specular_model; /* the lane's model number (specular.h); read only where lanes may differ */
  PrincipledSurface principled; /* with PRINCIPLED_V1, the lane's Principled parameters */
  PrincipledV2Surface principled_v2; /* with PRINCIPLED_V2, the lane's version 2 parameters */
  intv material;   /* material index, PHONGCL_BACKGROUND in background lanes */
} Surface;

/* Sums of Li*F*max(0, n.l) and Li*F*spec over the lights; the material multiplies once at the end. */
typedef struct {
  vec3 diffuse, specular;
} LightSums;

/* The three terms of L_o, before the host's radiance scale is undone. */
typedef struct {
  vec3 ambient, diffuse, specular;
} Terms;

/* The lights a work-item loops over. */
typedef struct {
  UNIFORM_SPACE const PointLight* point;             /* point and spot lights */
  UNIFORM_SPACE const LightShape* point_shapes;      /* parallel to point */
  UNIFORM_SPACE const LinkWord* point_links;         /* LIGHT_LINKING words per point light */
  UNIFORM_SPACE const DirectionalLight* directional;
  UNIFORM_SPACE const LinkWord* directional_links;   /* LIGHT_LINKING words per directional light */
  __global const uint* point_list;                   /* TILED_CULLING: the work-item's tile's lights */
  int point_count, directional_count;                /* lights to loop over (of point_list when culled) */
  int point_holding;                                 /* TILED_CULLING: the first this many of point_list hold
                                                        all of the tile in their bounds */
  UNIFORM_SPACE const AreaLightRecord* area;         /* AREA_LIGHTS: rects and disks */
  int area_count;
  UNIFORM_SPACE const uint* point_casters;           /* SHADOWS: where point light i casts shadows, 1 + its
                                                        place in the culling's casters (shadow.h), else 0 */
  UNIFORM_SPACE const uint* directional_casters;     /* SHADOWS: the same per directional light */
  UNIFORM_SPACE const uint* area_casters;            /* SHADOWS: the same per area light */
  UNIFORM_SPACE const SoftLight* point_soft;         /* SOFT_SHADOWS: rays and size per point light (1 ray: hard) */
  UNIFORM_SPACE const SoftLight* directional_soft;   /* SOFT_SHADOWS: the same per directional light */
  UNIFORM_SPACE const SoftLight* area_soft;          /* SOFT_SHADOWS: the same per area light */
  uint pixel;                                        /* SOFT_SHADOWS, ENVIRONMENT_SHADOWS: the frame pixel of the
                                                        work-item's first lane: each pixel's own lattice shift */
  const ShadowInputs* shadows;                       /* SHADOWS: what the shadow rays test (shadow.h) */
  UNIFORM_SPACE const uint* point_groups;            /* LIGHT_GROUPS: point light i's group, LIGHT_GROUPS for none */
  UNIFORM_SPACE const uint* directional_groups;      /* LIGHT_GROUPS: the same per directional light */
  UNIFORM_SPACE const uint* area_groups;             /* LIGHT_GROUPS: the same per area light */
  UNIFORM_SPACE const EnvironmentRecord* environment; /* ENVIRONMENT: the world's light */
  UNIFORM_SPACE const float* environment_texels;     /* ENVIRONMENT: its irradiance map */
  UNIFORM_SPACE const EnvironmentSun* environment_suns; /* ENVIRONMENT: its brightest cells as directional lights */
  UNIFORM_SPACE const EnvironmentLobe* environment_lobes; /* ENVIRONMENT and SPECULAR: each material's prefiltered lobe */
  uint environment_group;                            /* LIGHT_GROUPS: its group, LIGHT_GROUPS for none */
} Lights;

/* A work-item's slots of the G-buffer planes. */
typedef struct {
  __global const STORAGE* planes;
  uint stride;
  size_t group;
} PixelPlanes;

static inline realv pixel_plane(const PixelPlanes* pixels, int plane) {
  return TO_REALV(load_plane(pixels->planes, pixels->stride, plane, pixels->group));
}

/* Three planes from `plane` on. Loads stay out of functions that return structs (so this and
 * MATERIAL_FIELD3 are macros, and sum_lights and shade_pixel write through pointers): such a function
 * returns through a hidden no-alias pointer, once inlined its loads carry that pointer's alias scope,
 * and the compiler schedules the whole kernel differently for it. */
#define PIXEL_PLANE3(pixels, plane) \
  make_vec3(pixel_plane(pixels, plane), pixel_plane(pixels, (plane) + 1), pixel_plane(pixels, (plane) + 2))

/* Three fields of each lane's material, from `field` on (material.h). A macro also so that `field`
 * is a constant where the compiler first simplifies the selects. */
#define MATERIAL_FIELD3(materials, field) \
  make_vec3(material_field(materials, field), material_field(materials, (field) + 1), material_field(materials, (field) + 2))

/* A light's specular lobe where some lane of the vector may have a highlight, raised to the power
 * after the block's lights (sum_pending_lobes). Whether any lane has one follows no pattern a branch
 * predictor learns once a pixel has more than a few lights, and a mispredicted skip of the power cost
 * about what the power does; a block's lobes are counted into `lobes` instead, with no branch. */
typedef struct {
  realv cosine, one_minus_cosine; /* specular_power()'s arguments */
  realv factor;                   /* the power's factor: F where n.l > 0 (F n.l for a normalised lobe), else 0 */
  UNIFORM_SPACE const float* color;
} PendingLobe;

typedef struct {
  PendingLobe lobes[PHONGCL_LIGHT_BLOCK];
  int count;
} PendingLobes;

/* Whether a kind of light leaves its powers to sum_pending_lobes: in vectors of lanes, unless the
 * kernel holds a few of them (`count` in the code), whose skips a predictor learns (docs/kernel.md,
 * "Measured"). One lane per work-item (GPUs) keeps the branch: a GPU would keep the lobes in scratch
 * memory. */
#define DEFERS_LOBES(count) (PHONGCL_LANES > 1 && ((count) == 0 || (count) > 4))

/* Adds Li spec factor, spec the lobe's power: 0 where factor is (F may be +Inf where spec is 0). */
void add_specular(LightSums* sums, realv spec, realv factor, UNIFORM_SPACE const float* color) {
  const realv lit_spec = NONNEGATIVE_TIMES(spec, factor);
  sums->specular.x += NONNEGATIVE_TIMES(color[0], lit_spec);
  sums->specular.y += NONNEGATIVE_TIMES(color[1], lit_spec);
  sums->specular.z += NONNEGATIVE_TIMES(color[2], lit_spec);
}

/* What one light adds: the seed's formula for light i, without the material's kd and ks (the same
 * for every light: shade_pixel() multiplies the sums once),
 *   diffuse  += Li F_i max(0, n.l)
 *   specular += Li F_i max(0, v.r)^q,   r = 2(n.l)n - l  (Phong's lobe; the material's model: specular.h)
 * for a light of colour Li = `color`, weight F_i = `weight` (falloff, cone, linking, shadow: the
 * add_*_light() below) and direction l = toward * inverse (inverse = 1 / |toward|, 1 for a
 * directional light's unit vector). Where `pending` is not 0 the lobe waits there for its power
 * (sum_pending_lobes(), next).
 * How it is written: in place, not returned, each `sum += colour * lobe` contracts to one fma; nothing
 * waits for the light's square root before it must (the loop is latency-bound, and waiting makes a
 * point light's chain 50% longer); n, v and q come by value, not as the Surface: with the struct's
 * address passed this deep, PoCL keeps a copy of it per work-item (4 KB each with double16, past the
 * work-group's stack). */
void light_contribution(LightSums* sums, PendingLobes* pending, vec3 n, vec3 v, realv shininess, realv cutoff,
                        realv model, vec3 toward, realv inverse, UNIFORM_SPACE const float* color, realv weight) {
  const realv n_dot_toward = dot3(n, toward);
  const realv n_dot_l = n_dot_toward * inverse;                           /* n.l */
  const realv lit = SELECT(n_dot_l > 0, n_dot_l * weight, 0);             /* F max(0, n.l) */
  sums->diffuse.x += NONNEGATIVE_TIMES(color[0], lit);
  sums->diffuse.y += NONNEGATIVE_TIMES(color[1], lit);
  sums->diffuse.z += NONNEGATIVE_TIMES(color[2], lit);
  if (SPECULAR) {
    /* v.r (or the model's cosine) and 1 - it, which the power takes for accuracy near 1 */
    const LobeCosine lobe = lobe_cosine(n, v, toward, inverse, n_dot_toward, model);
    /* The power is half of a light's instructions and most of its dependency chain. Where every
     * lane faces away or is below the cutoff its terms are 0, and adding them changes no bit: left
     * out (half of the vectors and lights of the throughput bench's 256 lights), by the count of
     * pending lobes or by a branch. */
    const int dark = all_lanes(LANE_MASK(n_dot_l <= 0) | LANE_MASK(lobe.cosine < cutoff));
    /* F where n.l > 0 (a normalised lobe: F n.l), else 0: a light behind the surface has no highlight */
    realv factor = SELECT(n_dot_l > 0, weight, 0);
    if (NORMALIZED_LOBES) factor = SELECT(normalized_model(model) != 0, lit, factor);
    if (pending) {
      /* Written whether or not it is kept: the next light's lobe overwrites a dark one. */
      PendingLobe* next = &pending->lobes[pending->count];
      next->cosine = lobe.cosine;
      next->one_minus_cosine = lobe.one_minus_cosine;
      next->factor = factor;
      next->color = color;
      pending->count += !dark;
      return;
    }
    if (dark) return;
    add_specular(sums, specular_power(lobe.cosine, lobe.one_minus_cosine, shininess), factor, color); /* ^q */
  }
}

/* `share` in Principled v2 lanes, 1 in the others (with PRINCIPLED_V2). */
static inline vec3 v2_lanes_share(const Surface* surface, vec3 share) {
  const realv one = 1;
  if (ONLY_PRINCIPLED_V2) return share;
  return select3(share, make_vec3(one, one, one), SELECT(surface->specular_model == PRINCIPLED_V2_MODEL, 1, 0));
}

/* The share of an area light's Lambert light, from unit l toward its centre, a lane's diffuse takes: a
 * Principled v2 lane's under its dielectric layer (and Oren-Nayar's over Lambert's), all of it in the
 * others. */
static inline vec3 area_lambert_share(const Surface* surface, vec3 l) {
  const realv one = 1;
  if (!PRINCIPLED_V2) return make_vec3(one, one, one);
  return v2_lanes_share(surface, principled_v2_lambert_share(surface->principled_v2, surface->n, surface->v, l));
}

/* The same for the environment's light. */
static inline vec3 sky_lambert_share(const Surface* surface) {
  const realv one = 1;
  if (!PRINCIPLED_V2) return make_vec3(one, one, one);
  return v2_lanes_share(surface, principled_v2_sky_share(surface->principled_v2));
}

/* A Principled lane's responses (principled.h) in its version; where lanes mix the versions, both. */
static inline PrincipledResponse principled_lanes_response(const Surface* surface, vec3 l) {
  if (!PRINCIPLED_V2) return principled_response(surface->principled, surface->n, surface->v, l);
  const PrincipledResponse v2 = principled_v2_response(surface->principled_v2, surface->n, surface->v, l);
  if (!PRINCIPLED_V1) return v2;
  const PrincipledResponse v1 = principled_response(surface->principled, surface->n, surface->v, l);
  const realv is_v2 = SELECT(surface->specular_model == PRINCIPLED_V2_MODEL, 1, 0);
  PrincipledResponse response;
  response.diffuse = SELECT(is_v2 != 0, v2.diffuse, v1.diffuse);
  if (OREN_NAYAR) response.diffuse_multiple = v2.diffuse_multiple; /* M is 0 in other lanes */
  response.specular = select3(v2.specular, v1.specular, is_v2);
  return response;
}

/* What a Principled lane adds (principled.h): Li F times its responses, the specular one coloured. */
void principled_light(LightSums* sums, const Surface* surface, vec3 toward, realv inverse, UNIFORM_SPACE const float* color,
                      realv weight) {
  const PrincipledResponse response = principled_lanes_response(surface, scale3(toward, inverse));
  const realv lit = NONNEGATIVE_TIMES(weight, response.diffuse);
  if (OREN_NAYAR) {
    /* Version 2's Oren-Nayar: its multiple scattering coloured by the surface's M. */
    const vec3 m = surface->principled_v2.rough.multiple;
    const realv multiple = NONNEGATIVE_TIMES(weight, response.diffuse_multiple);
    sums->diffuse.x += NONNEGATIVE_TIMES(color[0], fma(m.x, multiple, lit));
    sums->diffuse.y += NONNEGATIVE_TIMES(color[1], fma(m.y, multiple, lit));
    sums->diffuse.z += NONNEGATIVE_TIMES(color[2], fma(m.z, multiple, lit));
  } else {
    sums->diffuse.x += NONNEGATIVE_TIMES(color[0], lit);
    sums->diffuse.y += NONNEGATIVE_TIMES(color[1], lit);
    sums->diffuse.z += NONNEGATIVE_TIMES(color[2], lit);
  }
  sums->specular.x += NONNEGATIVE_TIMES(color[0], NONNEGATIVE_TIMES(weight, response.specular.x));
  sums->specular.y += NONNEGATIVE_TIMES(color[1], NONNEGATIVE_TIMES(weight, response.specular.y));
  sums->specular.z += NONNEGATIVE_TIMES(color[2], NONNEGATIVE_TIMES(weight, response.specular.z));
}

/* A point, spot or directional light on each lane's material: the Phong-family lobes
 * (light_contribution), Principled ones (principled_light), or where lanes mix them both, each with
 * the other's lanes' weight 0. */
static inline void surface_light(LightSums* sums, PendingLobes* pending, const Surface* surface, vec3 toward,
                                 realv inverse, UNIFORM_SPACE const float* color, realv weight) {
  if (!PRINCIPLED_LOBES) {
    light_contribution(sums, pending, surface->n, surface->v, surface->shininess, surface->highlight_cutoff,
                       surface->specular_model, toward, inverse, color, weight);
    return;
  }
  const realv principled = ONLY_PRINCIPLED_LOBES ? 1 : SELECT(surface->specular_model >= PRINCIPLED_MODEL, 1, 0);
  principled_light(sums, surface, toward, inverse, color, SELECT(principled != 0, weight, 0));
  if (!ONLY_PRINCIPLED_LOBES)
    light_contribution(sums, pending, surface->n, surface->v, surface->shininess, surface->highlight_cutoff,
                       surface->specular_model, toward, inverse, color, SELECT(principled != 0, 0, weight));
}

/* The block's pending lobes (light_contribution) raised to the power q and added, in the lights' order. */
void sum_pending_lobes(LightSums* sums, const PendingLobes* pending, realv shininess) {
  for (int k = 0; k < pending->count; ++k) {
    const PendingLobe* lobe = &pending->lobes[k];
    add_specular(sums, specular_power(lobe->cosine, lobe->one_minus_cosine, shininess), lobe->factor, lobe->color);
  }
}

/* Each light's own lattice shift (sampling.h): point light i's stream i, the other kinds' from these. */
#define DIRECTIONAL_STREAMS 0x40000000u
#define AREA_STREAMS 0x80000000u
#define ENVIRONMENT_STREAM 0xC0000000u
#define ENVIRONMENT_SPECULAR_STREAM 0xC0000001u

/* F times the light's visibility: 0 in the lanes where its shadow ray is blocked (a select, not a
 * product: F may be +Inf at a light), traced only where the light casts shadows (`casts`, its
 * caster word) and lights the lane. `where` is a point light's eye-relative position or a
 * directional light's unit l. With SOFT_SHADOWS a light with a size (`soft`: more than one ray)
 * takes the visible fraction of its sphere or sun instead (soft_shadow.h), `stream` numbering its
 * lattice, and `cone` (a soft spot's shape, else 0) counted per ray; 0 stays a select. */
static inline SHADOW_INLINE realv shadowed_weight(realv weight, const Surface* surface, const Lights* lights,
                                                  vec3 where, int directional, uint casts,
                                                  UNIFORM_SPACE const SoftLight* soft, UNIFORM_SPACE const LightShape* cone,
                                                  uint stream) {
  if (!casts) return weight;
  const intv pending = LANE_MASK(weight > 0) & LANE_MASK(surface->material != PHONGCL_BACKGROUND);
  if (SOFT_SHADOWS && soft->rays > 1) {
    const Emitter emitter =
        directional ? sun_emitter(where, soft->size) : sphere_emitter(where, soft->size, surface->p);
    const realv visible = emitter_visibility(lights->shadows, surface->p, surface->n, &emitter, cone, casts - 1,
                                             soft->rays, lattice_shift(lights->pixel, stream), pending);
    return SELECT(visible > 0, weight * visible, 0);
  }
  const intv blocked =
      light_blocked(lights->shadows, surface->p, surface->n, where, directional, SCREEN_SHADOWS, casts - 1, pending);
  return SELECT(TO_REALV(blocked) != 0, 0, weight);
}

/* A point light's position and, with POSITION_REST, its rest (layout.h). Macros, as PIXEL_PLANE3. */
#define LIGHT_POSITION(light) make_vec3((light)->position[0], (light)->position[1], (light)->position[2])
#define LIGHT_REST(light) make_vec3((light)->position_rest[0], (light)->position_rest[1], (light)->position_rest[2])

/* L - P for a point light at `position` (+ `rest` with POSITION_REST). With the rests, the leading
 * parts' difference is exact where the light is near the surface (Sterbenz: within a factor of 2),
 * and the rests add what float positions relative to the eye lost: a light 1e-4 from a surface 1e4
 * from the eye is 1e-8 of the position, below float's rounding unit 6e-8. */
static inline vec3 light_offset(vec3 position, vec3 rest, const Surface* surface) {
#pragma clang fp reassociate(off) /* -cl-fast-relaxed-math would add the rests to the leading parts first */
  const vec3 leading = sub3(position, surface->p);
  if (!POSITION_REST) return leading;
  return make_vec3(leading.x + (rest.x - surface->p_rest.x), leading.y + (rest.y - surface->p_rest.y),
                   leading.z + (rest.z - surface->p_rest.z));
}

/* What a light with a size that casts soft shadows adds past light_contribution()'s max(0, n.l), to
 * the diffuse sum alone: its emitter lights a little beyond the horizon (horizon_cosine), where
 * sin_sq is its angular radius's sine squared. 0 wherever the emitter is wholly above or below it. */
static inline void add_horizon_light(LightSums* sums, vec3 n, vec3 toward, realv inverse, realv sin_sq,
                                     UNIFORM_SPACE const float* color, realv weight) {
  const realv c = dot3(n, toward) * inverse;
  const realv beyond = horizon_cosine(c, sin_sq) - fmax(c, (real)0);
  const realv lit = SELECT(beyond > 0, beyond * weight, 0); /* 0, not 0 * Inf, at the light */
  sums->diffuse.x += NONNEGATIVE_TIMES(color[0], lit);
  sums->diffuse.y += NONNEGATIVE_TIMES(color[1], lit);
  sums->diffuse.z += NONNEGATIVE_TIMES(color[2], lit);
}

/* What a point or spot light adds, F from its shape and linking mask, times its visibility with
 * SHADOWS. In a tile's list a spot whose cone leaves out every lane is left early: that changes no
 * bit of the sums. A light with a radius that casts soft shadows lights as its emitter does: a
 * spot's cone from the emitter's points (wider than the centre's: never left early) and a little
 * past the horizon. */
static inline void add_point_light(LightSums* sums, PendingLobes* pending, const Surface* surface,
                                   const Lights* lights, int i) {
  UNIFORM_SPACE const PointLight* light = &lights->point[i];
  UNIFORM_SPACE const LightShape* shape = &lights->point_shapes[i];
  UNIFORM_SPACE const LinkWord* link_mask = &lights->point_links[i * LIGHT_LINKING];
  const vec3 position = LIGHT_POSITION(light);
  vec3 toward = light_offset(position, LIGHT_REST(light), surface);
  realv distance = 0, inverse_distance = 0; /* spots alone read neither */
  const realv inverse = NEEDS_DISTANCE ? distance_in_range(&toward, &distance, &inverse_distance)
                                       : inverse_length_in_range(&toward);
  const bool soft = SOFT_SHADOWS && SHADOWS && lights->point_casters[i] && lights->point_soft[i].rays > 1;
  if (TILED_CULLING && SPOT_LIGHTS && (soft ? false : outside_cone_in_every_lane(shape, toward, inverse))) return;
  const realv gate = link_gate(link_mask, surface->material);
  realv weight = POINT_SHAPES ? shape_weight(shape, toward, inverse, distance, inverse_distance, gate, !soft) : gate;
  if (SHADOWS)
    weight = shadowed_weight(weight, surface, lights, position, 0, lights->point_casters[i], &lights->point_soft[i],
                             soft && SPOT_LIGHTS ? shape : 0, (uint)i);
  surface_light(sums, pending, surface, toward, inverse, light->color, weight);
  if (soft) {
    const realv tangent = lights->point_soft[i].size * inverse; /* of the disk facing P: r / d */
    add_horizon_light(sums, surface->n, toward, inverse, tangent * tangent / (1 + tangent * tangent), light->color, weight);
  }
}

/* What a directional light adds; F is its linking, times its visibility with SHADOWS; a sun with an
 * angle that casts soft shadows a little past the horizon too. */
static inline void add_directional_light(LightSums* sums, PendingLobes* pending, const Surface* surface,
                                         const Lights* lights, int k) {
  UNIFORM_SPACE const DirectionalLight* light = &lights->directional[k];
  UNIFORM_SPACE const LinkWord* link_mask = &lights->directional_links[k * LIGHT_LINKING];
  const vec3 l = make_vec3(light->to_light[0], light->to_light[1], light->to_light[2]);
  realv weight = link_gate(link_mask, surface->material);
  if (SHADOWS)
    weight = shadowed_weight(weight, surface, lights, l, 1, lights->directional_casters[k], &lights->directional_soft[k],
                             0, DIRECTIONAL_STREAMS + (uint)k);
  surface_light(sums, pending, surface, l, 1, light->color, weight);
  if (SOFT_SHADOWS && SHADOWS && lights->directional_casters[k] && lights->directional_soft[k].rays > 1) {
    const real tangent = lights->directional_soft[k].size; /* of the sun's angular radius */
    add_horizon_light(sums, surface->n, l, 1, tangent * tangent / (1 + tangent * tangent), light->color, weight);
  }
}

/* An area light's shadow. With SOFT_SHADOWS and more than one ray its E and S are multiplied by
 * the visible fraction of the emitter (soft_shadow.h). Otherwise the hard shadow: E and S are 0 in
 * the lanes where the one ray to the emitter's centre is blocked, as a point light's there would be
 * (lanes whose horizon hides the centre trace nothing and stay lit); selects, not products, as
 * shadowed_weight's. */
static inline void shadow_area_light(realv* irradiance, realv* highlight, const Surface* surface, const Lights* lights,
                                     int k, uint casts) {
  UNIFORM_SPACE const AreaLightRecord* light = &lights->area[k];
  const intv lit = LANE_MASK(*irradiance > 0) | LANE_MASK(*highlight > 0);
  const intv pending = lit & LANE_MASK(surface->material != PHONGCL_BACKGROUND);
  const uint rays = SOFT_SHADOWS ? lights->area_soft[k].rays : 1;
  if (rays > 1) {
    const Emitter emitter = area_emitter(light);
    const realv visible = emitter_visibility(lights->shadows, surface->p, surface->n, &emitter, 0, casts - 1, rays,
                                             lattice_shift(lights->pixel, AREA_STREAMS + (uint)k), pending);
    *irradiance *= visible;
    *highlight *= visible;
    return;
  }
  const intv blocked = light_blocked(lights->shadows, surface->p, surface->n, area_vector(light->center), 0,
                                     SCREEN_SHADOWS, casts - 1, pending);
  *irradiance = SELECT(TO_REALV(blocked) != 0, 0, *irradiance);
  *highlight = SELECT(TO_REALV(blocked) != 0, 0, *highlight);
}

/* The GGX lobe an area light's LTC integrates for each Principled lane: a v1 lane's own, a v2 lane's
 * of its alpha without Fresnel (f0 = 1, white), which ltc_v2_tint colours after. */
static inline PrincipledSurface ltc_lobe_surface(const Surface* surface) {
  if (!PRINCIPLED_V2) return surface->principled;
  const realv one = 1;
  PrincipledSurface white;
  white.specular_color = make_vec3(one, one, one);
  white.alpha_sq = surface->principled_v2.alpha_sq;
  white.roughness = sqrt(sqrt(white.alpha_sq));
  white.ior = surface->principled_v2.ior;
  white.f0 = one;
  if (!PRINCIPLED_V1) return white;
  const realv is_v2 = SELECT(surface->specular_model == PRINCIPLED_V2_MODEL, 1, 0);
  PrincipledSurface m = surface->principled;
  m.specular_color = select3(white.specular_color, m.specular_color, is_v2);
  m.alpha_sq = SELECT(is_v2 != 0, white.alpha_sq, m.alpha_sq);
  m.roughness = SELECT(is_v2 != 0, white.roughness, m.roughness);
  m.ior = SELECT(is_v2 != 0, white.ior, m.ior);
  m.f0 = SELECT(is_v2 != 0, one, m.f0);
  return m;
}

/* What an area light adds: Li E and Li S (area_light.h), with r = 2(n.v)n - v, times its visibility
 * with SHADOWS. */
static inline void add_area_light(LightSums* sums, const Surface* surface, const Lights* lights, int k) {
  UNIFORM_SPACE const AreaLightRecord* light = &lights->area[k];
  if (beyond_range_in_every_lane(sub3(area_vector(light->center), surface->p), (realv)light->inverse_range)) return;
  const vec3 n = surface->n, v = surface->v;
  const realv two_n_dot_v = 2 * dot3(n, v);
  const vec3 r = make_vec3(fma(two_n_dot_v, n.x, -v.x), fma(two_n_dot_v, n.y, -v.y), fma(two_n_dot_v, n.z, -v.z));
  realv irradiance, highlight;
  area_light_terms(light, surface->p, n, v, r, surface->shininess, surface->specular_model,
                   ONLY_PRINCIPLED_LOBES ? 0 : SPECULAR, &irradiance, &highlight);
  /* Principled lanes take Lambert's irradiance (v2's under its dielectric layer) and GGX's highlight
   * by LTC (area_ltc.h), coloured by v1's Fresnel or by v2's lobe over the white one: `tint`, 1 in
   * the other lanes. */
  const realv one = 1;
  vec3 tint = make_vec3(one, one, one);
  if (PRINCIPLED_LOBES && SPECULAR) {
    const PrincipledSurface lobe = ltc_lobe_surface(surface);
    const LtcHighlight ltc = ltc_area_highlight(light, surface->p, n, v, lobe);
    vec3 ltc_tint = ltc.tint;
    if (PRINCIPLED_V2) {
      const vec3 v2 = ltc_v2_tint(surface->principled_v2, lobe, ltc);
      ltc_tint = PRINCIPLED_V1 ? select3(v2, ltc_tint, SELECT(surface->specular_model == PRINCIPLED_V2_MODEL, 1, 0)) : v2;
    }
    const realv principled = ONLY_PRINCIPLED_LOBES ? 1 : SELECT(surface->specular_model >= PRINCIPLED_MODEL, 1, 0);
    highlight = SELECT(principled != 0, ltc.highlight, highlight);
    tint = select3(ltc_tint, tint, principled);
  }
  if (SHADOWS && lights->area_casters[k])
    shadow_area_light(&irradiance, &highlight, surface, lights, k, lights->area_casters[k]);
  if (PRINCIPLED_V2) {
    const vec3 toward = sub3(area_vector(light->center), surface->p);
    const vec3 share = area_lambert_share(surface, scale3(toward, rsqrt(max(dot3(toward, toward), (real)1e-30f))));
    sums->diffuse.x += light->color[0] * irradiance * share.x;
    sums->diffuse.y += light->color[1] * irradiance * share.y;
    sums->diffuse.z += light->color[2] * irradiance * share.z;
  } else {
    sums->diffuse.x += light->color[0] * irradiance;
    sums->diffuse.y += light->color[1] * irradiance;
    sums->diffuse.z += light->color[2] * irradiance;
  }
  if (SPECULAR && PRINCIPLED_LOBES) {
    sums->specular.x += light->color[0] * highlight * tint.x;
    sums->specular.y += light->color[1] * highlight * tint.y;
    sums->specular.z += light->color[2] * highlight * tint.z;
  } else if (SPECULAR) {
    sums->specular.x += light->color[0] * highlight;
    sums->specular.y += light->color[1] * highlight;
    sums->specular.z += light->color[2] * highlight;
  }
}

/* A Principled lane's specular albedo under a white world, in its version, for the environment's
 * split sum; 0 where no lane is Principled (then nothing reads it). */
static inline vec3 split_sum_albedo(const Surface* surface) {
  const realv zero = 0;
  const realv n_dot_v = clamp(dot3(surface->n, surface->v), zero, (realv)1);
  vec3 albedo = make_vec3(zero, zero, zero);
  if (PRINCIPLED_V1)
    albedo = principled_v1_specular_albedo(n_dot_v, surface->principled.roughness, surface->principled.specular_color);
  if (PRINCIPLED_V2) {
    const vec3 v2 = principled_v2_specular_albedo(surface->principled_v2, n_dot_v);
    albedo = PRINCIPLED_V1 ? select3(v2, albedo, SELECT(surface->specular_model == PRINCIPLED_V2_MODEL, 1, 0)) : v2;
  }
  return albedo;
}

/* What the environment adds: E(n) / pi to the diffuse sum (kd times it is the light a Lambertian
 * surface reflects), with ENVIRONMENT_SHADOWS from the directions nothing blocks; with SPECULAR each
 * material's prefiltered lobe at r to the specular sum, times the sky-weighted free share of rays in the lobe
 * with ENVIRONMENT_SHADOWS (environment_specular.h), and the suns as directional lights through
 * surface_light(). */
static inline void add_environment(LightSums* sums, const Surface* surface, const Lights* lights) {
  UNIFORM_SPACE const EnvironmentRecord* environment = lights->environment;
  vec3 light = environment_irradiance(environment, lights->environment_texels, surface->n);
  const intv pending =
      LANE_MASK(surface->material != PHONGCL_BACKGROUND) & LANE_MASK(dot3(surface->n, surface->n) > 0);
  const LatticeShift shift = lattice_shift(lights->pixel, ENVIRONMENT_STREAM);
  if (ENVIRONMENT_SHADOWS && SCREEN_SHADOWS)
    light = environment_horizon_light(lights->shadows, environment, lights->environment_texels, light, surface->p, surface->n,
                                      shift, pending);
  else if (ENVIRONMENT_SHADOWS)
    light = environment_visible_light(lights->shadows, environment, lights->environment_texels, light, surface->p, surface->n,
                                      shift, pending);
  /* Without a specular term the suns are diffuse light here; with one they are lights below. */
  if (!SPECULAR) {
    const vec3 suns =
        environment_suns(lights->environment_suns, environment->sun_count, lights->shadows, surface->p, surface->n, pending);
    light = add3(light, scale3(suns, (realv)environment->scale));
  }
  if (PRINCIPLED_V2) {
    const vec3 share = sky_lambert_share(surface);
    light = make_vec3(light.x * share.x, light.y * share.y, light.z * share.z);
  }
  sums->diffuse = add3(sums->diffuse, light);
  if (!SPECULAR) return;
  /* A few rays in each lane's lobe: an eighth of the diffuse light's, at least 1. */
  const realv visible =
      ENVIRONMENT_SHADOWS ? environment_specular_visibility(lights->shadows, environment, lights->environment_texels,
                                                            lights->environment_lobes, surface->material,
                                                            surface->p, surface->n, surface->v,
                                                            max(environment->rays / 8, 1u),
                                                            lattice_shift(lights->pixel, ENVIRONMENT_SPECULAR_STREAM), pending)
                          : 1;
  sums->specular = add3(sums->specular, environment_specular(environment, lights->environment_texels, lights->environment_lobes,
                                                             surface->material, surface->n, surface->v,
                                                             split_sum_albedo(surface), visible));
  ShadowInputs traced = *lights->shadows;
  traced.tiles = 0;
  for (int k = 0; k < environment->sun_count; ++k) {
    UNIFORM_SPACE const EnvironmentSun* sun = &lights->environment_suns[k];
    const vec3 d = environment_sun_direction(sun);
    const realv weight = environment->scale * environment_sun_visible(&traced, d, surface->p, surface->n, pending);
    surface_light(sums, 0, surface, d, 1, sun->color, weight);
  }
}

void add_block(LightSums* sums, LightSums* compensation, const LightSums* block) {
  kahan_add(&sums->diffuse.x, &compensation->diffuse.x, block->diffuse.x, WEIGHT_CAN_OVERFLOW);
  kahan_add(&sums->diffuse.y, &compensation->diffuse.y, block->diffuse.y, WEIGHT_CAN_OVERFLOW);
  kahan_add(&sums->diffuse.z, &compensation->diffuse.z, block->diffuse.z, WEIGHT_CAN_OVERFLOW);
  kahan_add(&sums->specular.x, &compensation->specular.x, block->specular.x, WEIGHT_CAN_OVERFLOW);
  kahan_add(&sums->specular.y, &compensation->specular.y, block->specular.y, WEIGHT_CAN_OVERFLOW);
  kahan_add(&sums->specular.z, &compensation->specular.z, block->specular.z, WEIGHT_CAN_OVERFLOW);
}

/* The kinds of light, each a table of the scene's block and a loop of sum_lights(). */
enum { POINT_KIND, DIRECTIONAL_KIND, AREA_KIND };

/* The loop driver: sums the lights of one kind into `sums` and `compensation`, with LIGHT_GROUPS
 * `group`'s only (the test is uniform: every lane skips the same lights). It owns how the lights are
 * visited, apart from what each adds (light_contribution()):
 * - Blocks: lights are summed in blocks of PHONGCL_LIGHT_BLOCK in plain float, and the block sums
 *   compensated (Kahan, add_block()): the error stays a few ulp plus one block's however many lights
 *   there are (10,000 lights, one of 1 then 9,999 of 3e-8: plain float 3.0e-4 relative, blocked Kahan
 *   4.5e-7). Counts in the code (up to 16) are one block. -cl-fast-relaxed-math may fold the
 *   compensation away (fast).
 * - Pending lobes: with DEFERS_LOBES a block's specular powers are taken after its lights.
 * - Culled lists: with TILED_CULLING the point lights are the tile's list, led by the lights whose
 *   bounds hold all of the tile (cull.cl); of the others each block first keeps those within range of
 *   some lane, counting rather than branching: a light left out changes no bit of the sums (its window
 *   is 0 in every lane), and which of a tile's lights miss a row of it follows no pattern a branch
 *   predictor learns (a mispredicted skip cost about what shading the light does).
 * Inlined at each call whatever its size, so that `kind` is a constant and the other kinds' code
 * folds away, as if each kind had its own loop. */
static inline __attribute__((always_inline)) void sum_light_kind(LightSums* sums, LightSums* compensation,
                                                                 const Surface* surface, const Lights* lights,
                                                                 int kind, int count, uint group) {
  const realv zero = 0;
  const LightSums no_light = {{zero, zero, zero}, {zero, zero, zero}};
  const int count_in_code = kind == POINT_KIND ? POINT_COUNT : kind == DIRECTIONAL_KIND ? DIRECTIONAL_COUNT : 0;
  for (int first = 0; first < count; first += PHONGCL_LIGHT_BLOCK) {
    const int last = min(first + PHONGCL_LIGHT_BLOCK, count);
    LightSums block = no_light;
    PendingLobes lobes;
    lobes.count = 0;
    PendingLobes* pending = SPECULAR && kind != AREA_KIND && DEFERS_LOBES(count_in_code) ? &lobes : 0;
    if (TILED_CULLING && kind == POINT_KIND) {
      int kept[PHONGCL_LIGHT_BLOCK], kept_count = 0;
      for (int k = first; k < last; ++k) {
        const int i = (int)lights->point_list[k];
        UNIFORM_SPACE const PointLight* light = &lights->point[i];
        const bool beyond = RANGE_WINDOW && k >= lights->point_holding &&
                            beyond_range_in_every_lane(light_offset(LIGHT_POSITION(light), LIGHT_REST(light), surface),
                                                       (realv)lights->point_shapes[i].inverse_range);
        const bool in_group = !LIGHT_GROUPS || lights->point_groups[i] == group;
        kept[kept_count] = i;
        kept_count += !beyond && in_group;
      }
      for (int k = 0; k < kept_count; ++k) add_point_light(&block, pending, surface, lights, kept[k]);
    } else if (kind == POINT_KIND) {
      for (int k = first; k < last; ++k)
        if (!LIGHT_GROUPS || lights->point_groups[k] == group) add_point_light(&block, pending, surface, lights, k);
    } else if (kind == DIRECTIONAL_KIND) {
      for (int k = first; k < last; ++k)
        if (!LIGHT_GROUPS || lights->directional_groups[k] == group)
          add_directional_light(&block, pending, surface, lights, k);
    } else {
      for (int k = first; k < last; ++k)
        if (!LIGHT_GROUPS || lights->area_groups[k] == group) add_area_light(&block, surface, lights, k);
    }
    if (pending) sum_pending_lobes(&block, pending, surface->shininess);
    add_block(sums, compensation, &block);
  }
}

/* The lights' sums for one vector of pixels (with LIGHT_GROUPS `group`'s lights only): each kind's
 * loop, compensated into one sum. */
static inline void sum_lights(LightSums* out, const Surface* surface, const Lights* lights, uint group) {
  const realv zero = 0;
  const LightSums no_light = {{zero, zero, zero}, {zero, zero, zero}};
  LightSums sums = no_light, compensation = no_light;
  if (POINT_LIGHTS) sum_light_kind(&sums, &compensation, surface, lights, POINT_KIND, lights->point_count, group);
  if (DIRECTIONAL_LIGHTS)
    sum_light_kind(&sums, &compensation, surface, lights, DIRECTIONAL_KIND, lights->directional_count, group);
  if (AREA_LIGHTS) sum_light_kind(&sums, &compensation, surface, lights, AREA_KIND, lights->area_count, group);
  if (ENVIRONMENT) {
    if (!LIGHT_GROUPS || lights->environment_group == group) {
      LightSums world = no_light;
      add_environment(&world, surface, lights);
      add_block(&sums, &compensation, &world);
    }
  }
  *out = sums;
}

/* Three planes of a term, unscaled. */
void store_term(__global float* out, uint stride, size_t group, vec3 term, float a, float b) {
  store_plane(unscale(term.x, a, b), group, out);
  store_plane(unscale(term.y, a, b), group, out + stride);
  store_plane(unscale(term.z, a, b), group, out + 2 * (size_t)stride);
}

/* A work-item's slots of the output planes. */
typedef struct {
  __global float* rgba;   /* R G B A */
  __global float* terms;  /* with WRITE_TERMS: ambient, diffuse, specular RGB, then the light groups' */
  uint stride;
  size_t group;
} PixelOutputs;

/* k*sum per channel, for the material's kd or ks and the lights' sums. */
static inline vec3 reflected(vec3 k, vec3 sum) {
  return make_vec3(NONNEGATIVE_TIMES(k.x, sum.x), NONNEGATIVE_TIMES(k.y, sum.y), NONNEGATIVE_TIMES(k.z, sum.z));
}

/* With LIGHT_GROUPS: the lights' sums group by group, the ungrouped lights last (as group
 * LIGHT_GROUPS), each group's kd*D_g + ks*S_g stored in its three planes after the terms, and the
 * groups' sums compensated into the total: ambient + the groups + the ungrouped lights = L_o. */
static inline void sum_groups(LightSums* out, const Surface* surface, const Lights* lights, vec3 kd, vec3 ks,
                              const PixelOutputs* outputs, float a, float b) {
  const realv zero = 0;
  const LightSums no_light = {{zero, zero, zero}, {zero, zero, zero}};
  LightSums sums = no_light, compensation = no_light;
  for (int g = 0; g <= LIGHT_GROUPS; ++g) {
    LightSums group;
    sum_lights(&group, surface, lights, (uint)g);
    if (g < LIGHT_GROUPS) {
      vec3 light = reflected(kd, group.diffuse);
      if (SPECULAR) {
        const vec3 specular = reflected(ks, group.specular);
        light = make_vec3(light.x + specular.x, light.y + specular.y, light.z + specular.z);
      }
      store_term(outputs->terms + (PHONGCL_TERM_PLANES + 3 * (size_t)g) * outputs->stride, outputs->stride,
                 outputs->group, light, a, b);
    }
    add_block(&sums, &compensation, &group);
  }
  *out = sums;
}

/* The specular sum's coefficient: ks, or 1 in Principled lanes, whose sums carry their colour (their ks
 * is the Fresnel's cspec0, principled.h). */
static inline vec3 specular_coefficient(vec3 ks, realv model) {
  if (!PRINCIPLED_LOBES) return ks;
  const realv one = 1;
  if (ONLY_PRINCIPLED_LOBES) return make_vec3(one, one, one);
  return select3(make_vec3(one, one, one), ks, SELECT(model >= PRINCIPLED_MODEL, 1, 0));
}

/* L_o's terms for one vector of pixels: ambient ka*La, diffuse kd*D, specular ks*S. */
static inline void shade_pixel(Terms* terms, const PixelPlanes* pixels, const MaterialLookup* materials,
                               const Lights* lights, const FrameScalars* frame, const PixelOutputs* outputs) {
  Surface surface;
  surface.material = materials->index;
  surface.shininess = PER_PIXEL_Q ? pixel_plane(pixels, PLANE_Q) : material_field(materials, MATERIAL_SHININESS);
  surface.highlight_cutoff = SPECULAR ? highlight_cutoff(surface.shininess) : 0;
  surface.specular_model = MIXED_SPECULAR_MODELS ? material_field(materials, MATERIAL_SPECULAR_MODEL) : 0;
  if (PRINCIPLED_V1) {
    surface.principled.specular_color = MATERIAL_FIELD3(materials, MATERIAL_KS);
    surface.principled.roughness = material_field(materials, MATERIAL_ROUGHNESS);
    surface.principled.alpha_sq = surface.principled.roughness * surface.principled.roughness;
    surface.principled.alpha_sq *= surface.principled.alpha_sq;
    surface.principled.ior = material_field(materials, MATERIAL_IOR);
    surface.principled.f0 = dielectric_fresnel((realv)1, surface.principled.ior);
  }
  surface.p = PIXEL_PLANE3(pixels, PLANE_PX);
  const realv zero = 0;
  surface.p_rest = POSITION_REST ? PIXEL_PLANE3(pixels, PLANE_REST) : make_vec3(zero, zero, zero);
  surface.n = unit_or_zero(PIXEL_PLANE3(pixels, PLANE_NX));
  surface.v = unit_or_zero(make_vec3(-surface.p.x, -surface.p.y, -surface.p.z)); /* v = normalize(E - P), E = 0 */
  if (PRINCIPLED_V2)
    surface.principled_v2 = principled_v2_surface(
        MATERIAL_FIELD3(materials, MATERIAL_METAL_F0), MATERIAL_FIELD3(materials, MATERIAL_METAL_B),
        material_field(materials, MATERIAL_METALLIC), MATERIAL_FIELD3(materials, MATERIAL_KS),
        material_field(materials, MATERIAL_DIELECTRIC_LAYER), material_field(materials, MATERIAL_ROUGHNESS),
        material_field(materials, MATERIAL_IOR), material_field(materials, MATERIAL_FRESNEL_AVERAGE),
        OREN_NAYAR ? material_field(materials, MATERIAL_DIFFUSE_ROUGHNESS) : (realv)0, clamp(dot3(surface.n, surface.v), (realv)0, (realv)1));

  /* D = sum_i Li F_i max(0, n.l_i), S = sum_i Li F_i max(0, v.r_i)^q (or the material's lobe) */
  LightSums sums;
  if (LIGHT_GROUPS) {
    const vec3 kd = PER_PIXEL_KD ? PIXEL_PLANE3(pixels, PLANE_KD) : MATERIAL_FIELD3(materials, MATERIAL_KD);
    const vec3 ks = specular_coefficient(PER_PIXEL_KS ? PIXEL_PLANE3(pixels, PLANE_KS) : MATERIAL_FIELD3(materials, MATERIAL_KS),
                                         surface.specular_model);
    sum_groups(&sums, &surface, lights, kd, ks, outputs, frame->radiance_scale_a, frame->radiance_scale_b);
  } else {
    sum_lights(&sums, &surface, lights, 0);
  }

  const Terms no_terms = {{zero, zero, zero}, {zero, zero, zero}, {zero, zero, zero}};
  *terms = no_terms;
  const vec3 kd = PER_PIXEL_KD ? PIXEL_PLANE3(pixels, PLANE_KD) : MATERIAL_FIELD3(materials, MATERIAL_KD);
  terms->diffuse = make_vec3(NONNEGATIVE_TIMES(kd.x, sums.diffuse.x), NONNEGATIVE_TIMES(kd.y, sums.diffuse.y),
                            NONNEGATIVE_TIMES(kd.z, sums.diffuse.z));
  if (SPECULAR) {
    const vec3 ks = specular_coefficient(PER_PIXEL_KS ? PIXEL_PLANE3(pixels, PLANE_KS) : MATERIAL_FIELD3(materials, MATERIAL_KS),
                                         surface.specular_model);
    /* The normalised lobes' factor, (q+2)/2 or (q+8)/8: constant over the lights, so applied once. */
    if (NORMALIZED_LOBES)
      sums.specular = scale3(sums.specular, specular_normalization(surface.shininess, surface.specular_model));
    terms->specular = make_vec3(NONNEGATIVE_TIMES(ks.x, sums.specular.x), NONNEGATIVE_TIMES(ks.y, sums.specular.y),
                               NONNEGATIVE_TIMES(ks.z, sums.specular.z));
  }
  if (AMBIENT) {
    const vec3 ka = PER_PIXEL_KA ? PIXEL_PLANE3(pixels, PLANE_KA) : MATERIAL_FIELD3(materials, MATERIAL_KA);
    terms->ambient = make_vec3(ka.x * frame->ambient[0], ka.y * frame->ambient[1], ka.z * frame->ambient[2]);
  }
}

/* R G B A = ambient + diffuse + specular, alpha 1, with the radiance scale a * b undone; background
 * lanes get the background colour and alpha 0. With WRITE_TERMS the terms too (in background lanes
 * whatever they hold: the host ignores terms where alpha is 0). */
static inline void store_pixels(const PixelOutputs* out, const Terms* terms, intv background,
                                const FrameScalars* frame, float a, float b) {
  __global float* out_rgba = out->rgba;
  __global float* out_terms = out->terms;
  const uint stride = out->stride;
  const size_t group = out->group;
  const floatv shaded_r = unscale(terms->ambient.x + terms->diffuse.x + terms->specular.x, a, b);
  const floatv shaded_g = unscale(terms->ambient.y + terms->diffuse.y + terms->specular.y, a, b);
  const floatv shaded_b = unscale(terms->ambient.z + terms->diffuse.z + terms->specular.z, a, b);
  store_plane(background ? (floatv)frame->background[0] : shaded_r, group, out_rgba);
  store_plane(background ? (floatv)frame->background[1] : shaded_g, group, out_rgba + stride);
  store_plane(background ? (floatv)frame->background[2] : shaded_b, group, out_rgba + 2 * (size_t)stride);
  store_plane(background ? (floatv)0.0f : (floatv)1.0f, group, out_rgba + 3 * (size_t)stride);
  if (WRITE_TERMS) {
    store_term(out_terms, stride, group, terms->ambient, a, b);
    store_term(out_terms + 3 * (size_t)stride, stride, group, terms->diffuse, a, b);
    store_term(out_terms + 6 * (size_t)stride, stride, group, terms->specular, a, b);
  }
}

/* A table of one of the kernel's blocks, at its word offset (FrameScalars' *Tables say where). */
#define TABLE(space, type, block, offset) ((space const type*)((block) + (offset)))

/* The host sets these arguments by name (host/shading/phong_arguments.h). A new table is an offset in
 * FrameScalars and an entry in its block, not a parameter. */
__kernel void phong_shade(
    /* G-buffer tile: planes (see layout.h, material.h), positions relative to the eye; each slot's
     * material, PHONGCL_BACKGROUND where not shaded */
    __global const STORAGE* restrict planes, __global const int* restrict material_index,
    /* ambient, background, radiance scales, light counts, plane stride, the tile grids, the shadow
     * scalars, and where each table starts in the blocks below (layout.h) */
    const FrameScalars frame,
    /* the scene's tables (SceneTables): materials, lights, light shapes, linking masks, area lights,
     * shadow casters, light groups; colours scaled by 2^-radiance_exponent, undone by the two scale
     * factors. Each is read only where the recipe compiles in what needs it. */
    UNIFORM_SPACE const uint* restrict scene,
    /* TILED_CULLING: the tiles' light lists (TileListTables, cull.cl) */
    __global const uint* restrict tile_lists,
    /* SHADOWS: the geometry and the screen march's depth plane (ShadowGeometryTables, shadow.h); with
     * frame.shadow_tiles > 0 tiled shadow culling's lists (ShadowListTables, shadow_cull.cl) */
    __global const uint* restrict shadow_geometry, __global const uint* restrict shadow_lists,
    /* output planes (PHONGCL_OUTPUT_PLANES): R G B A; with WRITE_TERMS also the terms (PHONGCL_TERM_PLANES),
     * then with LIGHT_GROUPS each group's three planes */
    __global float* restrict out_rgba, __global float* restrict out_terms) {
  const size_t group = get_global_id(0);
  const PixelOutputs outputs = {out_rgba, out_terms, frame.plane_stride, group};
  const float radiance_scale_a = frame.radiance_scale_a, radiance_scale_b = frame.radiance_scale_b;
  const uint first_pixel = (uint)(group * PHONGCL_LANES);
  const uint tile = TILED_CULLING ? tile_of_pixel(frame.grid, frame.grid.first_pixel + first_pixel) : 0;
  const uint shadow_tile =
      frame.shadow_tiles > 0 ? tile_of_pixel(frame.shadow_grid, frame.shadow_grid.first_pixel + first_pixel) : 0;
  const ShadowInputs shadows = {
      .nodes = TABLE(__global, BvhNode, shadow_geometry, frame.shadow_geometry.nodes),
      .primitives = TABLE(__global, ShadowPrimitive, shadow_geometry, frame.shadow_geometry.primitives),
      .planes = TABLE(__global, ShadowPlane, shadow_geometry, frame.shadow_geometry.planes),
      .depth = TABLE(__global, float, shadow_geometry, frame.shadow_geometry.depth),
      .frame = frame.shadow,
      .counts = TABLE(__global, uint, shadow_lists, frame.shadow_lists.counts),
      .offsets = TABLE(__global, uint, shadow_lists, frame.shadow_lists.offsets),
      .candidates = TABLE(__global, ShadowCandidate, shadow_lists, frame.shadow_lists.candidates),
      .tiles = frame.shadow_tiles,
      .tile = shadow_tile,
  };
  UNIFORM_SPACE const LinkWord* links = TABLE(UNIFORM_SPACE, LinkWord, scene, frame.scene.links);
  UNIFORM_SPACE const uint* casters = TABLE(UNIFORM_SPACE, uint, scene, frame.scene.shadow_casters);
  UNIFORM_SPACE const uint* groups = TABLE(UNIFORM_SPACE, uint, scene, frame.scene.light_groups);
  UNIFORM_SPACE const SoftLight* soft = TABLE(UNIFORM_SPACE, SoftLight, scene, frame.scene.soft_lights);
  __global const uint* tile_offsets = TABLE(__global, uint, tile_lists, frame.tile_lists.offsets);
  __global const uint* tile_lights = TABLE(__global, uint, tile_lists, frame.tile_lists.lights);
  const Lights lights = {
      .point = TABLE(UNIFORM_SPACE, PointLight, scene, frame.scene.point_lights),
      .point_shapes = TABLE(UNIFORM_SPACE, LightShape, scene, frame.scene.point_shapes),
      .point_links = links,
      .directional = TABLE(UNIFORM_SPACE, DirectionalLight, scene, frame.scene.directional_lights),
      .directional_links = links + frame.point_count * LIGHT_LINKING,
      .point_list = tile_lights + (TILED_CULLING ? tile_offsets[tile] : 0),
      .point_count = TILED_CULLING ? (int)TABLE(__global, uint, tile_lists, frame.tile_lists.counts)[tile]
                     : POINT_COUNT > 0 ? POINT_COUNT : frame.point_count,
      .point_holding = TILED_CULLING ? (int)TABLE(__global, uint, tile_lists, frame.tile_lists.holding)[tile] : 0,
      .directional_count = DIRECTIONAL_COUNT > 0 ? DIRECTIONAL_COUNT : frame.directional_count,
      .area = TABLE(UNIFORM_SPACE, AreaLightRecord, scene, frame.scene.area_lights),
      .area_count = frame.area_count,
      .point_casters = casters,
      .directional_casters = casters + frame.point_count,
      .area_casters = casters + frame.point_count + frame.directional_count,
      .point_soft = soft,
      .directional_soft = soft + frame.point_count,
      .area_soft = soft + frame.point_count + frame.directional_count,
      .pixel = frame.first_pixel + first_pixel,
      .shadows = &shadows,
      .point_groups = groups,
      .directional_groups = groups + frame.point_count,
      .area_groups = groups + frame.point_count + frame.directional_count,
      .environment = TABLE(UNIFORM_SPACE, EnvironmentRecord, scene, frame.scene.environment),
      .environment_texels = TABLE(UNIFORM_SPACE, float, scene, frame.scene.environment_texels),
      .environment_suns = TABLE(UNIFORM_SPACE, EnvironmentSun, scene, frame.scene.environment_suns),
      .environment_lobes = TABLE(UNIFORM_SPACE, EnvironmentLobe, scene, frame.scene.environment_lobes),
      .environment_group = LIGHT_GROUPS && ENVIRONMENT ? groups[frame.point_count + frame.directional_count + frame.area_count] : 0,
  };
  MaterialLookup material;
  look_up_materials(&material, TABLE(UNIFORM_SPACE, MaterialRecord, scene, frame.scene.materials), material_index,
                    group);
  const intv background = material.index == PHONGCL_BACKGROUND;
  const PixelPlanes pixels = {planes, frame.plane_stride, group};

  Terms terms;
  shade_pixel(&terms, &pixels, &material, &lights, &frame, &outputs);
  store_pixels(&outputs, &terms, background, &frame, radiance_scale_a, radiance_scale_b);
}
