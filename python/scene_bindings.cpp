// Scenes: load_scene, Scene.from_dict (the scene file's JSON form), and the structs as attributes.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "scene/scene.h"
#include "scene/scene_check.h"

namespace phongcl::python {

namespace {

std::string to_json(const py::handle& value) {
  return py::module_::import("json").attr("dumps")(value).cast<std::string>();
}

// A vec3 attribute of T, read and written as a 3-sequence of floats.
template <class T, class Class>
void vec3_property(Class& type, const char* name, glm::dvec3 T::*member, const char* doc) {
  type.def_property(
      name, [member](const T& self) { return to_array(self.*member); },
      [member](T& self, const std::array<double, 3>& value) { self.*member = to_vec3(value); }, doc);
}

}  // namespace

std::vector<Light> lights_from_python(const py::handle& lights) {
  try {
    return lights.cast<std::vector<Light>>();
  } catch (const py::cast_error&) {
    return parse_lights(to_json(lights), "lights");  // dicts in the scene file's form
  }
}

std::vector<Material> materials_from_python(const py::handle& materials) {
  try {
    return materials.cast<std::vector<Material>>();
  } catch (const py::cast_error&) {
    return parse_materials(to_json(materials), "materials");
  }
}

void bind_scene(py::module_& module) {
  py::class_<Camera> camera(module, "Camera", "The scene camera: the shader uses only the eye.");
  camera.def(py::init<>());
  vec3_property(camera, "eye", &Camera::eye, "Eye position, world space.");
  vec3_property(camera, "look_at", &Camera::look_at, "Point the camera looks at.");
  vec3_property(camera, "up", &Camera::up, "Up direction.");
  camera.def_readwrite("fov_y_deg", &Camera::fov_y_deg, "Vertical field of view, degrees.")
      .def_readwrite("width", &Camera::width)
      .def_readwrite("height", &Camera::height);

  py::class_<Light> light(module, "Light", "A point or directional light (README 'Scene').");
  light.def(py::init([](const std::string& type, std::array<double, 3> position, std::array<double, 3> direction,
                        std::array<double, 3> color) {
              return Light{type == "directional" ? LightType::directional
                           : type == "point"     ? LightType::point
                                                 : throw py::value_error("light type must be 'point' or "
                                                                         "'directional', not '" + type + "'"),
                           to_vec3(position), to_vec3(direction), to_vec3(color)};
            }),
            py::arg("type") = "point", py::arg("position") = std::array<double, 3>{0, 0, 0},
            py::arg("direction") = std::array<double, 3>{0, -1, 0}, py::arg("color") = std::array<double, 3>{1, 1, 1});
  light.def_property_readonly(
      "type", [](const Light& l) { return l.type == LightType::point ? "point" : "directional"; },
      "'point' or 'directional'.");
  vec3_property(light, "position", &Light::position, "Point lights: position.");
  vec3_property(light, "direction", &Light::direction, "Directional lights: the direction the light travels.");
  vec3_property(light, "color", &Light::color, "Radiance, RGB, >= 0.");
  light.def_readwrite("shadows", &Light::shadows,
                      "Casts shadows (as the Relighter's shadows= mode makes them; docs/shadows.md).");

  py::class_<Material> material(module, "Material", "A Phong material: ka, kd, ks (RGB) and shininess.");
  material.def(py::init<>()).def_readwrite("name", &Material::name).def_readwrite("shininess", &Material::shininess);
  vec3_property(material, "ka", &Material::ka, "Ambient reflectance.");
  vec3_property(material, "kd", &Material::kd, "Diffuse reflectance.");
  vec3_property(material, "ks", &Material::ks, "Specular reflectance.");

  py::class_<Scene> scene(module, "Scene",
                          "A scene: camera, ambient, background, lights, materials. Lists come out as copies: "
                          "assign a changed list back (scene.lights = lights).");
  scene.def(py::init<>())
      .def_static(
          "from_dict",
          [](const py::dict& description) { return parse_scene(to_json(description), "<dict>"); },
          py::arg("description"),
          "A scene from a dict in the scene file's JSON form; raises InputError naming the bad entry.")
      .def_readwrite("camera", &Scene::camera)
      .def_readwrite("lights", &Scene::lights)
      .def_readwrite("materials", &Scene::materials)
      .def_readonly("source", &Scene::source, "The scene file, or '<dict>'.");
  vec3_property(scene, "ambient", &Scene::ambient, "Ambient light La, RGB.");
  vec3_property(scene, "background", &Scene::background, "Colour of background pixels, RGB.");

  module.def("load_scene", &load_scene, py::arg("path"),
             "Reads and validates a scene file (JSON); raises InputError naming the file and the problem.");
}

}  // namespace phongcl::python
