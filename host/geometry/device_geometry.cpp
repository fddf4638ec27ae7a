#include "geometry/device_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace phongcl {
namespace {

// Float neighbours of a double on either side, so that a rounded box still holds what it bounds.
float round_down(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float round_up(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// The point of the triangle's plane nearest the eye (eye-relative), in double: far more exactly than
// the kernel could place the plane from its float corners, whose products of the triangle's size
// would lose its place near the eye. A plane within 2^-64 of the eye is moved there along its normal
// (the point gives the normal's direction, and float keeps it); a degenerate triangle gets 0.
glm::dvec3 plane_foot(const std::array<glm::dvec3, 3>& corners, const glm::dvec3& eye) {
  const glm::dvec3 normal = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
  const double length = glm::length(normal);
  if (!(length > 0.0)) return glm::dvec3(0.0);
  const glm::dvec3 unit = normal / length;
  const double distance = glm::dot(unit, corners[0] - eye);
  return unit * (std::abs(distance) >= 0x1p-64 ? distance : 0x1p-64);
}

// The triangle's corners, the sphere's map to the unit sphere (kernels/shadow_layout.h), eye-relative.
ShadowPrimitive pack_item(const SceneBvh& scene, std::uint32_t item, const glm::dvec3& eye) {
  ShadowPrimitive primitive{};
  const SceneShapes& shapes = scene.shapes;
  if (scene.group(item) == ShapeGroup::triangle) {
    const auto corners = shapes.corners(item);
    for (int row = 0; row < 3; ++row)
      for (int axis = 0; axis < 3; ++axis) primitive.row[row][axis] = static_cast<float>(corners[row][axis] - eye[axis]);
    double reach = 0.0;
    for (const glm::dvec3& corner : corners) reach = std::max(reach, glm::length(corner - eye));
    if (reach <= PHONGCL_SMALL_TRIANGLE_REACH) {
      const std::uint32_t small = PHONGCL_SMALL_TRIANGLE;
      std::memcpy(&primitive.row[0][3], &small, sizeof small);
      return primitive;
    }
    const glm::dvec3 foot = plane_foot(corners, eye);
    for (int axis = 0; axis < 3; ++axis) primitive.row[axis][3] = static_cast<float>(foot[axis]);
    return primitive;
  }
  // u = (W (x + eye) - c) / r for the world-to-object map W: A = W's linear part / r, b = (W eye - c) / r.
  const ShapeSphere& sphere = shapes.spheres[item - shapes.triangles.size()];
  const glm::dmat3 linear(sphere.world_to_object);
  const glm::dvec3 offset = (glm::dvec3(sphere.world_to_object * glm::dvec4(eye, 1.0)) - sphere.center) / sphere.radius;
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column)
      primitive.row[row][column] = static_cast<float>(linear[column][row] / sphere.radius);
    primitive.row[row][3] = static_cast<float>(offset[row]);
  }
  return primitive;
}

class NodePacker {
 public:
  NodePacker(const SceneBvh& scene, const glm::dvec3& eye, std::vector<BvhNode>& nodes)
      : scene_(scene), eye_(eye), nodes_(nodes) {}

  // The device node for host inner node `host` (or, at the root, a leaf beside an empty child).
  unsigned int pack(std::uint32_t host) {
    const auto index = static_cast<unsigned int>(nodes_.size());
    nodes_.emplace_back();
    const Bvh::Node& node = scene_.bvh.nodes[host];
    if (node.leaf()) {
      set_child(index, 0, node);
      set_empty(index, 1);
    } else {
      for (int c = 0; c < 2; ++c) set_child(index, c, scene_.bvh.nodes[node.first + c]);
    }
    return index;
  }

 private:
  void set_child(unsigned int index, int c, const Bvh::Node& child) {
    unsigned int first = 0, kind_count = BVH_INNER;
    if (child.leaf()) {
      const ShapeGroup group = scene_.group(scene_.bvh.order[child.first]);
      first = child.first;
      kind_count = (group == ShapeGroup::triangle ? BVH_TRIANGLES : BVH_SPHERES) | child.count << PHONGCL_BVH_KIND_BITS;
    } else {
      first = pack(static_cast<std::uint32_t>(&child - scene_.bvh.nodes.data()));
    }
    BvhNode& node = nodes_[index];  // after pack(): the vector may have moved
    node.lo_x[c] = round_down(child.box.lo.x - eye_.x);
    node.lo_y[c] = round_down(child.box.lo.y - eye_.y);
    node.lo_z[c] = round_down(child.box.lo.z - eye_.z);
    node.hi_x[c] = round_up(child.box.hi.x - eye_.x);
    node.hi_y[c] = round_up(child.box.hi.y - eye_.y);
    node.hi_z[c] = round_up(child.box.hi.z - eye_.z);
    node.first[c] = first;
    node.kind_count[c] = kind_count;
  }

  void set_empty(unsigned int index, int c) {
    BvhNode& node = nodes_[index];
    const float inf = std::numeric_limits<float>::infinity();
    node.lo_x[c] = node.lo_y[c] = node.lo_z[c] = inf;
    node.hi_x[c] = node.hi_y[c] = node.hi_z[c] = -inf;
    node.first[c] = 0;
    node.kind_count[c] = BVH_TRIANGLES;  // none of them
  }

  const SceneBvh& scene_;
  glm::dvec3 eye_;
  std::vector<BvhNode>& nodes_;
};

}  // namespace

DeviceGeometry pack_device_geometry(const SceneBvh& scene, const glm::dvec3& eye) {
  DeviceGeometry device;
  device.primitives.reserve(scene.bvh.order.size());
  device.bounds.reserve(scene.bvh.order.size());
  for (std::uint32_t item : scene.bvh.order) {
    device.primitives.push_back(pack_item(scene, item, eye));
    const Box box = scene.group(item) == ShapeGroup::triangle ? scene.shapes.triangle_box(item)
                                                              : scene.shapes.sphere_box(item - scene.shapes.triangles.size());
    device.bounds.push_back({{round_down(box.lo.x - eye.x), round_down(box.lo.y - eye.y), round_down(box.lo.z - eye.z)},
                             {round_up(box.hi.x - eye.x), round_up(box.hi.y - eye.y), round_up(box.hi.z - eye.z)}});
  }
  if (!scene.bvh.nodes.empty()) {
    device.nodes.reserve(scene.bvh.nodes.size() / 2 + 1);
    NodePacker(scene, eye, device.nodes).pack(0);
  }
  for (const ShapePlane& plane : scene.shapes.planes) {
    device.planes.push_back({{static_cast<float>(plane.normal.x), static_cast<float>(plane.normal.y),
                              static_cast<float>(plane.normal.z)},
                             static_cast<float>(plane.offset - glm::dot(plane.normal, eye))});
  }
  return device;
}

// Per item of the BVH: its box, centre, group and place in the order while building, and at most two
// nodes (a binary tree over leaves of at least one item), in the build's layout and the device's;
// per triangle its corners' indices, and its packed primitive and bounds on the host and the device.
double shadow_geometry_bytes(const ShapeCounts& counts) {
  constexpr double kPerItem = sizeof(Box) + sizeof(glm::dvec3) + sizeof(std::uint8_t) + sizeof(std::uint32_t) +
                              2 * (sizeof(Bvh::Node) + 2 * sizeof(BvhNode));
  constexpr double kPerTriangle = sizeof(ShapeTriangle) + 2 * (sizeof(ShadowPrimitive) + sizeof(ShadowBounds));
  constexpr double kPerSphere = sizeof(ShapeSphere) + 2 * (sizeof(ShadowPrimitive) + sizeof(ShadowBounds));
  const double items = static_cast<double>(counts.triangles + counts.spheres);
  return items * kPerItem + static_cast<double>(counts.triangles) * kPerTriangle +
         static_cast<double>(counts.spheres) * kPerSphere + static_cast<double>(counts.vertices) * sizeof(glm::dvec3);
}

}  // namespace phongcl
