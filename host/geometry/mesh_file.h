#pragma once
// A mesh object's triangles, read from its file with Assimp (PLY, OBJ, glTF and the other formats
// Assimp knows): polygons triangulated, the file's own node transforms applied, points and lines
// dropped. The scene's transforms are applied later (geometry/scene_shapes.h).
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

namespace phongcl {

struct TriangleMesh {
  std::vector<glm::vec3> vertices;                      // as stored in the file (single precision)
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into vertices
};

// At most this many triangles per file: the device layout keeps a primitive index in 30 bits.
inline constexpr std::size_t kMaxMeshTriangles = std::size_t{1} << 28;

// Throws InputError naming the file: unreadable or malformed, no triangles, a vertex that is not
// finite, more than kMaxMeshTriangles triangles.
TriangleMesh read_mesh(const std::filesystem::path& file);

struct MeshCounts {
  std::uint64_t vertices = 0, triangles = 0;
};

// What read_mesh would return, counted before it allocates it: a PLY file's from its checked header
// and lists (geometry/ply_check.h: nothing allocated per element), another format's by reading it.
// Throws as read_mesh does.
MeshCounts count_mesh(const std::filesystem::path& file);

}  // namespace phongcl
