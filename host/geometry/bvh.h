#pragma once
// A bounding volume hierarchy over boxes, built with the surface area heuristic over binned
// centroids (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"): at each
// node, 16 bins per axis, the split that minimises the expected cost of a ray that reaches the
// node. Hand-written rather than taken from a library: Debian packages no BVH builder but Embree's,
// which is a lab peer here and never linked by the product, and the layout the kernels read
// (kernels/shadow_layout.h) is ours to choose.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/scene_shapes.h"

namespace phongcl {

struct Bvh {
  // count == 0: an inner node whose children are nodes[first] and nodes[first + 1];
  // count > 0: a leaf of the items order[first] ... order[first + count - 1].
  struct Node {
    Box box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
    bool leaf() const { return count > 0; }
  };
  std::vector<Node> nodes;           // nodes[0] is the root (when there are items)
  std::vector<std::uint32_t> order;  // item indices, leaf by leaf
  int depth = 0;                     // levels below the root
};

// Leaves hold at most this many items.
inline constexpr std::uint32_t kBvhMaxLeafItems = 4;

// Items are boxes; a leaf holds items of one group only (say, triangles or spheres, which the
// kernel intersects differently). Items with an empty box are left out. The tree is at most
// max_depth levels deep below its root whatever the input (coincident or degenerate items):
// past a depth where the heuristic could exceed it, nodes are split at their median. Throws
// std::length_error when even median splits cannot keep within max_depth (2^max_depth items).
Bvh build_bvh(const std::vector<Box>& boxes, const std::vector<std::uint8_t>& groups, int max_depth);

}  // namespace phongcl
