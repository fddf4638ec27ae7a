#include "scene/object_json.h"

#include <algorithm>

#include "common/error.h"
#include "scene/transform.h"

namespace phongcl {
namespace {

// The largest |coordinate| of a triangle's corner (docs/shadows.md).
constexpr double kLargestCoordinate = 1e30;

int read_material(const JsonObject& object, std::size_t material_count) {
  int material = Object{}.material;
  if (auto value = object.find("material")) material = value->integer();
  if (material < 0 || static_cast<std::size_t>(material) >= material_count)
    object.value().fail("material index " + std::to_string(material) + " is out of range (the scene has " +
                        std::to_string(material_count) + " materials)");
  return material;
}

void read_sphere(const JsonObject& object, Object& sphere) {
  object.expect_keys({"type", "center", "radius", "material"});
  if (auto value = object.find("center")) sphere.center = value->vec3();
  if (auto value = object.find("radius")) {
    sphere.radius = value->number();
    if (!(sphere.radius > 0.0)) value->fail("must be > 0 (got " + format_number(sphere.radius) + ")");
  }
}

void read_plane(const JsonObject& object, Object& plane) {
  object.expect_keys({"type", "normal", "offset", "material"});
  if (auto value = object.find("normal")) {
    plane.normal = value->vec3();
    if (plane.normal == glm::dvec3(0.0)) value->fail("must not be zero");
  }
  if (auto value = object.find("offset")) plane.offset = value->number();
}

void read_triangle(const JsonObject& object, Object& triangle) {
  object.expect_keys({"type", "vertices", "material"});
  const JsonValue vertices = object.at("vertices");
  const std::vector<JsonValue> corners = vertices.elements();
  if (corners.size() != 3) vertices.fail("must be an array of 3 points");
  for (std::size_t i = 0; i < 3; ++i) {
    triangle.vertices[i] = corners[i].vec3();
    // A directional light's shadow ray ends at 2^100 (1.27e30), and the shadow tests are checked
    // to 1e30 (stability catalogue's huge occluders).
    const glm::dvec3 size = glm::abs(triangle.vertices[i]);
    if (std::max({size.x, size.y, size.z}) > kLargestCoordinate)
      corners[i].fail("has a coordinate beyond +-" + format_number(kLargestCoordinate) +
                      " (shadow rays reach 2^100, about 1.27e30)");
  }
  // A zero-area triangle can never be hit; say so rather than render nothing.
  const auto& v = triangle.vertices;
  if (glm::cross(v[1] - v[0], v[2] - v[0]) == glm::dvec3(0.0)) vertices.fail("must not be collinear");
}

// The file is resolved relative to the scene file, as "gbuffer" is; reading it is the geometry
// room's job (geometry/mesh_file.h), when shadows or the generator need the triangles.
void read_mesh(const JsonObject& object, Object& mesh) {
  object.expect_keys({"type", "file", "material"});
  const JsonValue file = object.at("file");
  const std::filesystem::path path = file.string();
  if (path.empty()) file.fail("must not be empty");
  mesh.file = path.is_absolute() ? path : file.file().parent_path() / path;
}

void read_transform(const JsonObject& object, Object& transform, std::size_t material_count) {
  object.expect_keys({"type", "matrix", "translate", "rotate_deg", "scale", "children"});
  const bool has_parts = object.has("translate") || object.has("rotate_deg") || object.has("scale");
  if (auto matrix = object.find("matrix")) {
    if (has_parts)
      object.value().fail("has both 'matrix' and 'translate'/'rotate_deg'/'scale' (use one form)");
    transform.matrix = matrix_from_row_major(matrix->numbers(16));
    if (!is_affine(transform.matrix)) matrix->fail("must be affine (last row 0, 0, 0, 1)");
  } else {
    glm::dvec3 translate(0.0), rotate_deg(0.0), scale(1.0);
    if (auto value = object.find("translate")) translate = value->vec3();
    if (auto value = object.find("rotate_deg")) rotate_deg = value->vec3();
    if (auto value = object.find("scale")) scale = value->vec3();
    transform.matrix = compose_transform(translate, rotate_deg, scale);
  }
  if (is_singular(transform.matrix)) object.value().fail("transform is singular (cannot be inverted)");
  if (auto children = object.find("children")) transform.children = read_objects(*children, material_count);
}

Object read_object(const JsonValue& value, std::size_t material_count) {
  const JsonObject object = value.object();
  const std::string type = object.at("type").string();
  Object result;
  if (type == "sphere") {
    result.kind = Object::Kind::sphere;
    read_sphere(object, result);
  } else if (type == "plane") {
    result.kind = Object::Kind::plane;
    read_plane(object, result);
  } else if (type == "triangle") {
    result.kind = Object::Kind::triangle;
    read_triangle(object, result);
  } else if (type == "mesh") {
    result.kind = Object::Kind::mesh;
    read_mesh(object, result);
  } else if (type == "transform") {
    result.kind = Object::Kind::transform;
    read_transform(object, result, material_count);
    return result;  // a transform has no material of its own
  } else {
    throw InputError(value.file(), "unknown object type '" + type + "' in " + value.place() +
                                       " (expected sphere, plane, triangle, mesh or transform)");
  }
  result.material = read_material(object, material_count);
  return result;
}

}  // namespace

std::vector<Object> read_objects(const JsonValue& array, std::size_t material_count) {
  std::vector<Object> objects;
  for (const JsonValue& element : array.elements()) objects.push_back(read_object(element, material_count));
  return objects;
}

}  // namespace phongcl
