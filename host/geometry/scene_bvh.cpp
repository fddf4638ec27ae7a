#include "geometry/scene_bvh.h"

namespace phongcl {

SceneBvh build_scene_bvh(SceneShapes shapes, int max_depth) {
  std::vector<Box> boxes;
  std::vector<std::uint8_t> groups;
  boxes.reserve(shapes.bounded_count());
  groups.reserve(shapes.bounded_count());
  for (std::size_t i = 0; i < shapes.triangles.size(); ++i) {
    boxes.push_back(shapes.triangle_box(i));
    groups.push_back(static_cast<std::uint8_t>(ShapeGroup::triangle));
  }
  for (std::size_t i = 0; i < shapes.spheres.size(); ++i) {
    boxes.push_back(shapes.sphere_box(i));
    groups.push_back(static_cast<std::uint8_t>(ShapeGroup::sphere));
  }
  SceneBvh scene;
  scene.bvh = build_bvh(boxes, groups, max_depth);
  scene.shapes = std::move(shapes);
  return scene;
}

}  // namespace phongcl
