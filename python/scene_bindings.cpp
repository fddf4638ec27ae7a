// Scenes: load_scene, Scene.from_dict (the scene file's JSON form), and the structs as attributes.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "color/color_conversion.h"
#include "scene/environment_json.h"
#include "scene/json_reader.h"
#include "scene/scene.h"
#include "scene/scene_check.h"

namespace phongcl::python {

namespace {

Scene in_working_space(Scene scene, const std::string& ocio) {
  if (!scene.color_space.empty()) convert_scene_colors(scene, color_config(ocio));
  return scene;
}

// The scene file's nesting limit (scene/json_reader.h), for self-referencing lists too.
constexpr int kMaxDepth = 256;

// Python's dicts, lists, tuples, NumPy arrays and scalars, numbers and strings as a JSON document,
// without going through text: NaN and infinities stay numbers, which the scene reader refuses as
// not finite, and NumPy values need no tolist() from the caller.
nlohmann::json json_of(const py::handle& value, int depth = 0) {
  if (depth > kMaxDepth) throw py::value_error("nested deeper than " + std::to_string(kMaxDepth) + " levels");
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<long long>();
    } catch (const py::cast_error&) {
      return value.cast<double>();  // beyond 64 bits: as large a number as it is
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::json object = nlohmann::json::object();
    for (const auto& [key, item] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key)) throw py::type_error("dict keys must be str, not " + py::repr(key).cast<std::string>());
      object[key.cast<std::string>()] = json_of(item, depth + 1);
    }
    return object;
  }
  if (py::hasattr(value, "tolist")) return json_of(value.attr("tolist")(), depth + 1);  // NumPy arrays and scalars
  if (py::isinstance<py::sequence>(value)) {
    nlohmann::json array = nlohmann::json::array();
    for (const auto& item : value.cast<py::sequence>()) array.push_back(json_of(item, depth + 1));
    return array;
  }
  throw py::type_error("expected numbers, strings, lists, dicts or NumPy arrays, not " +
                       py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

// A vec3 attribute of T, read and written as a 3-sequence of floats.
template <class T, class Class>
void vec3_property(Class& type, const char* name, glm::dvec3 T::*member, const char* doc) {
  type.def_property(
      name, [member](const T& self) { return to_array(self.*member); },
      [member](T& self, const std::array<double, 3>& value) { self.*member = to_vec3(value); }, doc);
}

// A list attribute of T, read as a list of copies and set whole.
template <class T, class Item, class Class>
void copied_list_property(Class& type, const char* name, std::vector<Item> T::*member, const char* doc) {
  type.def_property(
      name, [member](const T& self) { return self.*member; },
      [member](T& self, const std::vector<Item>& value) { self.*member = value; }, doc);
}

}  // namespace

std::vector<Light> lights_from_python(const py::handle& lights) {
  try {
    return lights.cast<std::vector<Light>>();
  } catch (const py::cast_error&) {
    return read_lights(json_of(lights), "lights");  // dicts in the scene file's form
  }
}

std::vector<AreaLight> area_lights_from_python(const py::handle& lights) {
  try {
    return lights.cast<std::vector<AreaLight>>();  // checked by set_area_lights, as set_lights checks Lights
  } catch (const py::cast_error&) {
    return read_area_lights(json_of(lights), "area_lights");  // dicts in the scene file's form
  }
}

std::optional<EnvironmentLight> environment_from_python(const py::handle& environment) {
  if (environment.is_none()) return std::nullopt;
  const nlohmann::json document = json_of(environment);
  const std::filesystem::path source = "environment";
  return read_environment_light(JsonValue(document, "environment", source).object(), source);
}

std::vector<Material> materials_from_python(const py::handle& materials) {
  try {
    return materials.cast<std::vector<Material>>();
  } catch (const py::cast_error&) {
    return read_materials(json_of(materials), "materials");
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

  py::class_<Light> light(module, "Light", "A point, spot or directional light (docs/formats.md 'Lights').");
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
  light.def_readwrite("radius", &Light::radius, "Point lights: a sphere's radius, for a soft shadow (0: a point).");
  light.def_readwrite("angle_deg", &Light::angle_deg,
                      "Directional lights: the sun's angular diameter in degrees, for a soft shadow (0: none).");
  light.def_readwrite("shadow_rays", &Light::shadow_rays,
                      "Rays for a soft shadow, 1 to 1024; 0: the Relighter's shadow_rays.");
  light.def_readwrite("group", &Light::group,
                      "Light group ('' for none): Relighter.shade_terms() returns each group's light apart.");

  py::class_<AreaLight> area(module, "AreaLight",
                             "A rect or disk emitter, one-sided (docs/formats.md 'Area lights'); the scene file's "
                             "{\"type\": \"area\", ...} entries come back as these.");
  area.def(py::init<>());
  area.def_property(
      "shape", [](const AreaLight& a) { return std::string(to_string(a.shape)); },
      [](AreaLight& a, const std::string& name) { a.shape = parse_area_shape(name); },
      "'rect' or 'disk'.");
  vec3_property(area, "position", &AreaLight::position, "The emitter's centre.");
  vec3_property(area, "direction", &AreaLight::direction, "The emitting side's normal (any length but zero).");
  vec3_property(area, "up", &AreaLight::up, "Rect: where its height runs (projected off direction).");
  area.def_property(
      "size", [](const AreaLight& a) { return std::array<double, 2>{a.size.x, a.size.y}; },
      [](AreaLight& a, const std::array<double, 2>& size) { a.size = {size[0], size[1]}; },
      "Rect: (width, height); disk: (diameter, diameter).");
  vec3_property(area, "color", &AreaLight::color, "Radiance, RGB, >= 0.");
  area.def_readwrite("range", &AreaLight::range, "> 0: windowed to 0 at this distance from the centre; 0: no range.")
      .def_readwrite("shadows", &AreaLight::shadows, "Casts a shadow: soft, or hard with one ray (shadow_rays).")
      .def_readwrite("shadow_rays", &AreaLight::shadow_rays,
                     "Geometry shadows' rays over the emitter, 1 to 1024 (1: one ray to the centre); 0: the "
                     "Relighter's shadow_rays.")
      .def_readwrite("group", &AreaLight::group, "Light group ('' for none).");

  py::class_<Material> material(module, "Material", "A Phong material: ka, kd, ks (RGB) and shininess.");
  material.def(py::init<>()).def_readwrite("name", &Material::name).def_readwrite("shininess", &Material::shininess);
  vec3_property(material, "ka", &Material::ka, "Ambient reflectance.");
  vec3_property(material, "kd", &Material::kd, "Diffuse reflectance.");
  vec3_property(material, "ks", &Material::ks, "Specular reflectance.");
  material.def_property(
      "specular_model", [](const Material& m) { return std::string(to_string(m.specular_model)); },
      [](Material& m, const std::string& name) { m.specular_model = parse_specular_model(name); },
      "'phong' (default), 'phong-normalized', 'blinn-phong', 'blinn-phong-normalized' or 'principled' "
      "(docs/shading.md).");
  vec3_property(material, "base_color", &Material::base_color, "principled: the base colour.");
  material.def_readwrite("metallic", &Material::metallic, "principled: metallic, [0, 1].")
      .def_readwrite("roughness", &Material::roughness, "principled: roughness, [0, 1].")
      .def_readwrite("specular", &Material::specular, "principled: specular, [0, 12] (F0 = 0.08 specular).")
      .def_readwrite("specular_tint", &Material::specular_tint, "principled version 1: specular tint, [0, 1].")
      .def_readwrite("version", &Material::version, "principled: the node's version, 1 (Blender 2.8 to 3.6) or 2 (4.0 on).")
      .def_readwrite("ior", &Material::ior, "principled version 2: the dielectric's index, [1, 1000].")
      .def_readwrite("specular_ior_level", &Material::specular_ior_level,
                     "principled version 2: Specular IOR Level, >= 0 (F0 times twice it).")
      .def_readwrite("diffuse_roughness", &Material::diffuse_roughness,
                     "principled version 2: Diffuse Roughness, [0, 1] (Oren-Nayar's; 0 is Lambert's).");
  vec3_property(material, "specular_tint_color", &Material::specular_tint_color,
                "principled version 2: the Specular Tint colour (the JSON's specular_tint).");

  py::class_<Scene> scene(module, "Scene",
                          "A scene: camera, ambient, background, lights, area lights, materials. Lists come out as copies: "
                          "assign a changed list back (scene.lights = lights).");
  scene.def(py::init<>())
      .def_static(
          "from_dict",
          [](const py::dict& description, const std::string& ocio) {
            return in_working_space(read_scene(json_of(description), "<dict>"), ocio);
          },
          py::arg("description"), py::arg("ocio") = "",
          "A scene from a dict in the scene file's JSON form, its colours in the working space of the OCIO config "
          "`ocio` (as --ocio: a file, 'blender', 'builtin'; default $OCIO, else built-in) when it names a "
          "\"color_space\"; raises InputError naming the bad entry.")
      .def_readwrite("camera", &Scene::camera)
      .def_readonly("source", &Scene::source, "The scene file, or '<dict>'.");
  // Lists of copies, set whole: a list of references into the scene's vectors would dangle once the
  // vector is replaced (scene.lights = ..., or a Relighter's set_lights) and the list is used again.
  copied_list_property(scene, "lights", &Scene::lights, "The point, spot and directional lights (copies: set the list whole).");
  copied_list_property(scene, "area_lights", &Scene::area_lights, "The area lights (copies: set the list whole).");
  copied_list_property(scene, "materials", &Scene::materials, "The material table (copies: set the list whole).");
  vec3_property(scene, "ambient", &Scene::ambient, "Ambient light La, RGB.");
  vec3_property(scene, "background", &Scene::background, "Colour of background pixels, RGB.");

  module.def(
      "load_scene", [](const std::filesystem::path& path, const std::string& ocio) { return in_working_space(load_scene(path), ocio); },
      py::arg("path"), py::arg("ocio") = "",
      "Reads and validates a scene file (JSON), its colours in the working space of the OCIO config `ocio` when it "
      "names a \"color_space\"; raises InputError naming the file and the problem.");
}

}  // namespace phongcl::python
