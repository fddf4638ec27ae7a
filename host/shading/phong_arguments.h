#pragma once
// phong_shade's arguments (kernels/phong.cl), by name: fill a PhongArguments with designated
// initialisers and set_arguments() sets each at its parameter's position. The kernel reads its tables
// from a few blocks: a new table is an entry in a block and its offset in FrameScalars, not an
// argument. A test checks the names and their order against the kernel's own (CL_KERNEL_ARG_NAME).
#include <string>
#include <vector>

#include "cl/opencl.h"
#include "shading/device_layout.h"

namespace phongcl {

struct PhongArguments {
  // G-buffer tile
  cl::Buffer planes{};          // recipe.plane_count() planes of plane_stride values (half with half-storage)
  cl::Buffer material_index{};  // one int per slot, PHONGCL_BACKGROUND where not shaded
  // ambient, background, radiance scales, light counts, plane stride, the tile grids, the shadow
  // scalars, and where each table starts in the blocks below (kernels/layout.h)
  FrameScalars frame{};
  // the blocks of tables (one buffer each, read only where the recipe compiles in what needs them)
  cl::Buffer scene{};            // SceneTables: materials, lights, shapes, links, area lights, casters, groups
  cl::Buffer tile_lists{};       // TileListTables: tiled culling's light lists
  cl::Buffer shadow_geometry{};  // ShadowGeometryTables: the BVH, primitives, planes, the depth plane
  cl::Buffer shadow_lists{};     // ShadowListTables: tiled shadow culling's candidates
  // output
  cl::Buffer out_rgba{};   // PHONGCL_OUTPUT_PLANES planes
  cl::Buffer out_terms{};  // PHONGCL_TERM_PLANES planes (then the light groups') with WRITE_TERMS, else unused
};

// visit(name, field) for every argument, in phong_shade's parameter order.
template <typename Arguments, typename Visit>
void for_each_argument(Arguments& a, Visit&& visit) {
  visit("planes", a.planes);
  visit("material_index", a.material_index);
  visit("frame", a.frame);
  visit("scene", a.scene);
  visit("tile_lists", a.tile_lists);
  visit("shadow_geometry", a.shadow_geometry);
  visit("shadow_lists", a.shadow_lists);
  visit("out_rgba", a.out_rgba);
  visit("out_terms", a.out_terms);
}

// The kernel's parameter names as the host sets them, in order.
std::vector<std::string> phong_argument_names();

// Sets every argument of a phong_shade kernel. Not thread-safe for one kernel object: one kernel
// object per thread that launches.
void set_arguments(cl::Kernel& kernel, const PhongArguments& arguments);

}  // namespace phongcl
