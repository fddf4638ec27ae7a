/* Deferred Phong shading, one work-item per pixel:
 *   L_o = ka*La + sum_i Li * [ kd*max(0, n.l_i) + ks*max(0, v.r_i)^q ],  r = 2(n.l)n - l
 * Only what the scene needs is compiled in. The host (host/shading/recipe.cpp) writes the options;
 * `phongcl shade --explain` prints them:
 *   POINT_LIGHTS, DIRECTIONAL_LIGHTS   light types present
 *   POINT_COUNT=n, DIRECTIONAL_COUNT=n compile-time light counts (loops unroll), else run-time
 *   SPECULAR, AMBIENT                  terms present
 *   SINGLE_MATERIAL                    every shaded pixel uses materials[0]: no per-pixel fetch
 *   PLANE_KA=k PLANE_KD=k PLANE_KS=k PLANE_Q=k   per-pixel material planes and where they are
 *   UNIFORM_SPACE=__constant|__global  where the light and material tables live
 *   HALF_STORAGE                       G-buffer planes stored as half (vload_half)
 *   PHONGCL_DOUBLE, PHONGCL_FAST       arithmetic precision (see phong_math.h)
 *   WRITE_TERMS                        also write ambient, diffuse, specular separately (AOVs)
 */
#include "layout.h"
#include "phong_math.h"

#ifdef HALF_STORAGE
#define STORAGE half
#define LOAD_PLANE(plane, i) ((real)vload_half((size_t)(plane) * plane_stride + (i), planes))
#else
#define STORAGE float
#define LOAD_PLANE(plane, i) ((real)planes[(size_t)(plane) * plane_stride + (i)])
#endif

#ifdef POINT_COUNT
#define POINT_LOOP_COUNT POINT_COUNT
#else
#define POINT_LOOP_COUNT point_count
#endif
#ifdef DIRECTIONAL_COUNT
#define DIRECTIONAL_LOOP_COUNT DIRECTIONAL_COUNT
#else
#define DIRECTIONAL_LOOP_COUNT directional_count
#endif

/* Sums of Li*max(0, n.l) and Li*spec over the lights; the material multiplies once at the end. */
typedef struct {
  vec3 diffuse, specular;
} LightSums;

/* Adds one light's contribution, with l the unit vector towards the light. */
inline void add_light(LightSums* sums, vec3 n, vec3 v, vec3 l, vec3 color, real shininess) {
  real ndl = dot3(n, l);
  if (!(ndl > 0)) return; /* back-facing or grazing: nothing from this light */
  sums->diffuse.x += color.x * ndl;
  sums->diffuse.y += color.y * ndl;
  sums->diffuse.z += color.z * ndl;
#ifdef SPECULAR
  vec3 r = sub3(scale3(n, 2 * ndl), l);
  vec3 v_minus_r = sub3(v, r);
  real spec = specular_power(dot3(v, r), (real)0.5 * dot3(v_minus_r, v_minus_r), shininess);
  sums->specular.x += color.x * spec;
  sums->specular.y += color.y * spec;
  sums->specular.z += color.z * spec;
#endif
}

/* Undoes the host's radiance scaling by 2^e = a * b: two power-of-two factors, each a normal float,
 * so the result overflows only when the exact one does. */
inline float unscale(real value, float a, float b) { return (float)(value * a) * b; }

inline vec3 light_color(const UNIFORM_SPACE float* color) { return make_vec3(color[0], color[1], color[2]); }

__kernel void phong_shade(
    /* G-buffer tile: planes (see layout.h), positions relative to the eye */
    __global const STORAGE* planes, uint plane_stride,
    __global const int* material_index,
    /* scene; colours scaled by 2^-radiance_exponent, undone by the two scale factors */
    UNIFORM_SPACE const MaterialRecord* materials,
    UNIFORM_SPACE const PointLight* point_lights, int point_count,
    UNIFORM_SPACE const DirectionalLight* directional_lights, int directional_count,
    float ambient_r, float ambient_g, float ambient_b,
    float radiance_scale_a, float radiance_scale_b,
    float background_r, float background_g, float background_b,
    /* output: RGBA float, interleaved; with WRITE_TERMS also 9 floats per pixel: ambient, diffuse,
     * specular RGB (one-element dummy otherwise) */
    __global float* out_rgba, __global float* out_terms) {
  const size_t i = get_global_id(0);
  __global float* out = out_rgba + 4 * i;
  const int material = material_index[i];
  if (material == PHONGCL_BACKGROUND) {
    out[0] = background_r;
    out[1] = background_g;
    out[2] = background_b;
    out[3] = 0.0f;
#ifdef WRITE_TERMS
    for (int k = 0; k < 9; ++k) out_terms[9 * i + k] = 0.0f;
#endif
    return;
  }

#ifdef SINGLE_MATERIAL
  UNIFORM_SPACE const MaterialRecord* record = &materials[0];
#else
  UNIFORM_SPACE const MaterialRecord* record = &materials[material];
#endif
#ifdef PLANE_Q
  const real shininess = LOAD_PLANE(PLANE_Q, i);
#else
  const real shininess = record->shininess;
#endif

  /* The eye is the origin: v = normalize(E - P) = normalize(-P). */
  const vec3 p = make_vec3(LOAD_PLANE(PLANE_PX, i), LOAD_PLANE(PLANE_PY, i), LOAD_PLANE(PLANE_PZ, i));
  const vec3 n = unit_or_zero(make_vec3(LOAD_PLANE(PLANE_NX, i), LOAD_PLANE(PLANE_NY, i), LOAD_PLANE(PLANE_NZ, i)));
  const vec3 v = unit_or_zero(make_vec3(-p.x, -p.y, -p.z));

  LightSums sums = {{0, 0, 0}, {0, 0, 0}};
#ifdef POINT_LIGHTS
  for (int k = 0; k < POINT_LOOP_COUNT; ++k) {
    UNIFORM_SPACE const PointLight* light = &point_lights[k];
    vec3 to_light = sub3(make_vec3(light->position[0], light->position[1], light->position[2]), p);
    add_light(&sums, n, v, unit_or_zero(to_light), light_color(light->color), shininess);
  }
#endif
#ifdef DIRECTIONAL_LIGHTS
  for (int k = 0; k < DIRECTIONAL_LOOP_COUNT; ++k) {
    UNIFORM_SPACE const DirectionalLight* light = &directional_lights[k];
    vec3 l = make_vec3(light->to_light[0], light->to_light[1], light->to_light[2]);
    add_light(&sums, n, v, l, light_color(light->color), shininess);
  }
#endif

#ifdef PLANE_KD
  const vec3 kd = make_vec3(LOAD_PLANE(PLANE_KD, i), LOAD_PLANE(PLANE_KD + 1, i), LOAD_PLANE(PLANE_KD + 2, i));
#else
  const vec3 kd = make_vec3(record->kd[0], record->kd[1], record->kd[2]);
#endif
  const vec3 diffuse = make_vec3(kd.x * sums.diffuse.x, kd.y * sums.diffuse.y, kd.z * sums.diffuse.z);
#ifdef SPECULAR
#ifdef PLANE_KS
  const vec3 ks = make_vec3(LOAD_PLANE(PLANE_KS, i), LOAD_PLANE(PLANE_KS + 1, i), LOAD_PLANE(PLANE_KS + 2, i));
#else
  const vec3 ks = make_vec3(record->ks[0], record->ks[1], record->ks[2]);
#endif
  const vec3 specular = make_vec3(ks.x * sums.specular.x, ks.y * sums.specular.y, ks.z * sums.specular.z);
#else
  const vec3 specular = make_vec3(0, 0, 0);
#endif
#ifdef AMBIENT
#ifdef PLANE_KA
  const vec3 ka = make_vec3(LOAD_PLANE(PLANE_KA, i), LOAD_PLANE(PLANE_KA + 1, i), LOAD_PLANE(PLANE_KA + 2, i));
#else
  const vec3 ka = make_vec3(record->ka[0], record->ka[1], record->ka[2]);
#endif
  const vec3 ambient = make_vec3(ka.x * ambient_r, ka.y * ambient_g, ka.z * ambient_b);
#else
  const vec3 ambient = make_vec3(0, 0, 0);
#endif

  out[0] = unscale(ambient.x + diffuse.x + specular.x, radiance_scale_a, radiance_scale_b);
  out[1] = unscale(ambient.y + diffuse.y + specular.y, radiance_scale_a, radiance_scale_b);
  out[2] = unscale(ambient.z + diffuse.z + specular.z, radiance_scale_a, radiance_scale_b);
  out[3] = 1.0f;
#ifdef WRITE_TERMS
  const vec3 terms[3] = {ambient, diffuse, specular};
  for (int t = 0; t < 3; ++t) {
    out_terms[9 * i + 3 * t + 0] = unscale(terms[t].x, radiance_scale_a, radiance_scale_b);
    out_terms[9 * i + 3 * t + 1] = unscale(terms[t].y, radiance_scale_a, radiance_scale_b);
    out_terms[9 * i + 3 * t + 2] = unscale(terms[t].z, radiance_scale_a, radiance_scale_b);
  }
#endif
}
