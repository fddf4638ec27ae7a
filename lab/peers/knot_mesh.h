#pragma once
// A mesh scene for the shadow benchmarks: a trefoil knot's tube (as many triangles as asked, every
// one casting shadows on the tube itself and on a ground of two triangles), written as a binary
// little-endian PLY and read back through the product's mesh reader, as a user's file would be.
#include <cstddef>
#include <filesystem>

#include "geometry/mesh_file.h"
#include "scene/scene.h"

namespace phongcl {

// The tube: `segments` rings along the knot of `sides` vertices each, 2 x segments x sides
// triangles, about 4 units across, centred 2.2 above the ground plane y = 0.
TriangleMesh trefoil_knot(int segments, int sides);

// Binary little-endian PLY (x y z floats, faces as uchar-counted int lists). Throws
// std::runtime_error when the file cannot be written.
void write_ply(const std::filesystem::path& file, const TriangleMesh& mesh);

// The knot written to `directory`/knot.ply (segments x sides as above) and a 640x480 camera on it,
// the knot and a 40 x 40 ground as two triangles, two materials, and `lights` point lights
// above it, every one casting shadows.
Scene knot_scene(const std::filesystem::path& directory, int segments, int sides, int lights);

}  // namespace phongcl
