#pragma once
// phong_shade's arguments (kernels/phong.cl), by name: fill a PhongArguments with designated
// initialisers and set_arguments() sets each at its parameter's position. A new argument is a
// parameter of the kernel, a field here and a line in for_each_argument(); a test checks the names
// and their order against the kernel's own (CL_KERNEL_ARG_NAME).
#include <string>
#include <vector>

#include "cl/opencl.h"
#include "shading/device_layout.h"

extern "C" {
#include "kernels/shadow_layout.h"
}

namespace phongcl {

struct PhongArguments {
  // G-buffer tile
  cl::Buffer planes;          // recipe.plane_count() planes of plane_stride values (half with half-storage)
  cl::Buffer material_index;  // one int per slot, PHONGCL_BACKGROUND where not shaded
  // scene: colours scaled by 2^-radiance_exponent
  cl::Buffer materials, point_lights, directional_lights;
  FrameScalars frame{};  // ambient, background, radiance scales, light counts, plane stride
  // output
  cl::Buffer out_rgba;   // PHONGCL_OUTPUT_PLANES planes
  cl::Buffer out_terms;  // PHONGCL_TERM_PLANES planes with WRITE_TERMS, else unused
  // light shapes (parallel to point_lights) and linking masks, read only when compiled in
  cl::Buffer point_shapes, links;
  // tiled culling: tile t's point lights are tile_lights[tile_offsets[t] ...], tile_counts[t] of them,
  // the first tile_holding[t] of them holding all of the tile in their bounds
  cl::Buffer tile_offsets, tile_counts, tile_holding, tile_lights;
  TileGrid grid{};
  // shadows (kernels/shadow.h), read only with SHADOWS: a caster word per light (point lights',
  // directional lights', area lights'); the geometry; the screen march's depth plane; the scalars;
  // with shadow_tiles > 0 tiled shadow culling's lists over shadow_grid's tiles
  cl::Buffer shadow_casters, shadow_nodes, shadow_primitives, shadow_planes, shadow_depth;
  ShadowFrame shadow_frame{};
  cl::Buffer shadow_counts, shadow_offsets, shadow_candidates;
  TileGrid shadow_grid{};
  cl_uint shadow_tiles = 0;
  // light groups, read only with LIGHT_GROUPS: each light's group (point lights', then directional
  // lights'); their layers follow the terms in out_terms
  cl::Buffer light_groups;
  // area lights (kernels/area_light.h), read only with AREA_LIGHTS
  cl::Buffer area_lights;
};

// visit(name, field) for every argument, in phong_shade's parameter order.
template <typename Arguments, typename Visit>
void for_each_argument(Arguments& a, Visit&& visit) {
  visit("planes", a.planes);
  visit("material_index", a.material_index);
  visit("materials", a.materials);
  visit("point_lights", a.point_lights);
  visit("directional_lights", a.directional_lights);
  visit("frame", a.frame);
  visit("out_rgba", a.out_rgba);
  visit("out_terms", a.out_terms);
  visit("point_shapes", a.point_shapes);
  visit("links", a.links);
  visit("tile_offsets", a.tile_offsets);
  visit("tile_counts", a.tile_counts);
  visit("tile_holding", a.tile_holding);
  visit("tile_lights", a.tile_lights);
  visit("grid", a.grid);
  visit("shadow_casters", a.shadow_casters);
  visit("shadow_nodes", a.shadow_nodes);
  visit("shadow_primitives", a.shadow_primitives);
  visit("shadow_planes", a.shadow_planes);
  visit("shadow_depth", a.shadow_depth);
  visit("shadow_frame", a.shadow_frame);
  visit("shadow_counts", a.shadow_counts);
  visit("shadow_offsets", a.shadow_offsets);
  visit("shadow_candidates", a.shadow_candidates);
  visit("shadow_grid", a.shadow_grid);
  visit("shadow_tiles", a.shadow_tiles);
  visit("light_groups", a.light_groups);
  visit("area_lights", a.area_lights);
}

// The kernel's parameter names as the host sets them, in order.
std::vector<std::string> phong_argument_names();

// Sets every argument of a phong_shade kernel. Not thread-safe for one kernel object: one kernel
// object per thread that launches.
void set_arguments(cl::Kernel& kernel, const PhongArguments& arguments);

}  // namespace phongcl
