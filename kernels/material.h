/* Each lane's material: its coefficients from the scene's table by the lane's material index, or
 * from the G-buffer's per-pixel planes where it has them (PER_PIXEL_KA, _KD, _KS, _Q). */
#ifndef PHONGCL_MATERIAL_H
#define PHONGCL_MATERIAL_H

#include "features.h"
#include "layout.h"
#include "phong_math.h"

/* The per-pixel material planes follow the geometry planes, in this order, only if present, and
 * with POSITION_REST the three planes of what the position planes' float rounding lost (the host
 * packs them so: host/shading/pack.cpp). */
#define PLANE_KA PLANE_GEOMETRY_COUNT
#define PLANE_KD (PLANE_KA + 3 * PER_PIXEL_KA)
#define PLANE_KS (PLANE_KD + 3 * PER_PIXEL_KD)
#define PLANE_Q (PLANE_KS + 3 * PER_PIXEL_KS)
#define PLANE_REST (PLANE_Q + PER_PIXEL_Q)

/* A work-item's lanes' entries of the material table. Background lanes read entry 0 (the kernel
 * replaces them by the background colour). */
typedef struct {
  UNIFORM_SPACE const MaterialRecord* table;
  intv index;                 /* PHONGCL_BACKGROUND in background lanes */
  int entry[PHONGCL_LANES];  /* each lane's entry, 0 in background lanes; filled only where gathered */
} MaterialLookup;

/* Whether each lane's entry is needed one by one: a table neither of one material nor picked by
 * selects. With more than one lane, the lanes' fields are then gathered. */
#define PER_LANE_ENTRIES (!SINGLE_MATERIAL && MATERIAL_COUNT == 0)
#define GATHER_MATERIALS (PER_LANE_ENTRIES && PHONGCL_LANES > 1)

static inline void look_up_materials(MaterialLookup* lookup, UNIFORM_SPACE const MaterialRecord* table,
                                     __global const int* material_index, size_t group) {
  lookup->table = table;
  lookup->index = VLOAD(group, material_index);
  if (PER_LANE_ENTRIES)
    for (int k = 0; k < PHONGCL_LANES; ++k) lookup->entry[k] = max(material_index[group * PHONGCL_LANES + k], 0);
}

/* One field of a material record; `field` is a float offset within MaterialRecord (layout.h),
 * read through the named array it falls in (indexing past ka[4] is undefined behaviour; `field` is
 * a constant at every call, so the choice folds away). Through a function returning a private
 * value: clang 15 (PoCL 3.1) crashes on a vector literal cast straight from a __constant lvalue. */
real material_scalar(UNIFORM_SPACE const MaterialRecord* record, int field) {
  return field < MATERIAL_KD ? record->ka[field - MATERIAL_KA]
         : field < MATERIAL_KS ? record->kd[field - MATERIAL_KD]
         : field < MATERIAL_SHININESS ? record->ks[field - MATERIAL_KS]
         : field == MATERIAL_SHININESS ? record->shininess
         : field == MATERIAL_SPECULAR_MODEL ? record->specular_model
         : field == MATERIAL_ROUGHNESS ? record->roughness
         : field == MATERIAL_IOR ? record->ior
         : field < MATERIAL_METAL_B ? record->metal_f0[field - MATERIAL_METAL_F0]
         : field < MATERIAL_FRESNEL_AVERAGE ? record->metal_b[field - MATERIAL_METAL_B]
         : field == MATERIAL_FRESNEL_AVERAGE ? record->fresnel_average
                                             : record->diffuse_roughness;
}

/* `value`, or entry m's field in the lanes whose index is m. */
static inline realv select_entry(UNIFORM_SPACE const MaterialRecord* table, realv lane_index, int m, int field,
                                 realv value) {
  return m < MATERIAL_COUNT ? SELECT(lane_index == (real)m, material_scalar(&table[m], field), value) : value;
}

/* A table of MATERIAL_COUNT <= PHONGCL_LANES entries: each lane's field is picked by comparing its
 * index with every entry (uniform loads and selects). PoCL lowers per-lane gathers, and shuffles
 * with a variable mask, through per-work-item private memory, most of a frame without lights
 * (docs/kernel.md, "Measured"). Background lanes (index -1) get entry 0. Written out rather than a
 * loop: the comparisons are shared by every field only once unrolled, and `#pragma unroll` is a hint
 * a compiler may drop (docs/kernel.md, "Unrolling"). */
realv select_field(UNIFORM_SPACE const MaterialRecord* table, intv index, int field) {
  const realv lane_index = TO_REALV(index);
  realv value = (realv)material_scalar(&table[0], field);
  value = select_entry(table, lane_index, 1, field, value), value = select_entry(table, lane_index, 2, field, value);
  value = select_entry(table, lane_index, 3, field, value), value = select_entry(table, lane_index, 4, field, value);
  value = select_entry(table, lane_index, 5, field, value), value = select_entry(table, lane_index, 6, field, value);
  value = select_entry(table, lane_index, 7, field, value), value = select_entry(table, lane_index, 8, field, value);
  value = select_entry(table, lane_index, 9, field, value), value = select_entry(table, lane_index, 10, field, value);
  value = select_entry(table, lane_index, 11, field, value), value = select_entry(table, lane_index, 12, field, value);
  value = select_entry(table, lane_index, 13, field, value), value = select_entry(table, lane_index, 14, field, value);
  return select_entry(table, lane_index, 15, field, value);
}

/* One field of each lane's material record: a gather through private memory (no dynamic lane
 * indexing in OpenCL C). */
realv gather_field(UNIFORM_SPACE const MaterialRecord* table, const int* entry, int field) {
  real values[PHONGCL_LANES];
  for (int k = 0; k < PHONGCL_LANES; ++k) values[k] = material_scalar(&table[entry[k]], field);
  return VLOAD(0, values);
}

/* Field `field` of each lane's material. */
static inline realv material_field(const MaterialLookup* lookup, int field) {
  if (MATERIAL_COUNT > 0) return select_field(lookup->table, lookup->index, field);
  if (GATHER_MATERIALS) return gather_field(lookup->table, lookup->entry, field);
  /* One material for the whole work-item: a uniform load. */
  return (realv)material_scalar(&lookup->table[SINGLE_MATERIAL ? 0 : lookup->entry[0]], field);
}

#endif
