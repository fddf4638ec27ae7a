// parse_scene and load_scene: the scene file's sections, each read strictly (see json_reader.h).
#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/error.h"
#include "scene/area_light_json.h"
#include "scene/environment_json.h"
#include "scene/json_reader.h"
#include "scene/object_json.h"
#include "scene/scene.h"
#include "scene/scene_check.h"

namespace phongcl {
namespace {

// Colours and reflection coefficients: HDR values above 1 are fine, negative ones are not.
glm::dvec3 read_non_negative_vec3(const JsonValue& value) {
  const glm::dvec3 vector = value.vec3();
  const std::vector<JsonValue> components = value.elements();
  for (int i = 0; i < 3; ++i)
    if (vector[i] < 0.0) components[i].fail("must be >= 0 (got " + format_number(vector[i]) + ")");
  return vector;
}

int read_image_size(const JsonValue& value) {
  const int size = value.integer();
  if (size < 1) value.fail("must be >= 1 (got " + std::to_string(size) + ")");
  return size;
}

Camera read_camera(const JsonObject& object) {
  object.expect_keys({"eye", "look_at", "up", "fov_y_deg", "width", "height"});
  Camera camera;
  camera.eye = object.at("eye").vec3();
  if (auto value = object.find("look_at")) camera.look_at = value->vec3();
  if (auto value = object.find("up")) camera.up = value->vec3();
  if (auto value = object.find("fov_y_deg")) {
    camera.fov_y_deg = value->number();
    if (!(camera.fov_y_deg > 0.0 && camera.fov_y_deg < 180.0))
      value->fail("must be in (0, 180) degrees (got " + format_number(camera.fov_y_deg) + ")");
  }
  if (auto value = object.find("width")) camera.width = read_image_size(*value);
  if (auto value = object.find("height")) camera.height = read_image_size(*value);

  // The generator builds its basis from these; a degenerate one would give NaN rays.
  const glm::dvec3 forward = camera.look_at - camera.eye;
  if (forward == glm::dvec3(0.0)) object.value().fail("look_at must differ from eye");
  const double sine = glm::length(glm::cross(forward, camera.up)) /
                      (glm::length(forward) * glm::length(camera.up));
  if (!(sine > 1e-9)) object.value().fail("up must not be zero or parallel to the view direction");
  return camera;
}

Falloff read_falloff(const JsonValue& value) {
  const std::string name = value.string();
  for (Falloff falloff : {Falloff::none, Falloff::linear, Falloff::quadratic, Falloff::cubic})
    if (name == to_string(falloff)) return falloff;
  value.fail("'" + name + "' is not a falloff (expected none, linear, quadratic or cubic)");
}

double read_positive(const JsonValue& value) {
  const double number = value.number();
  if (!(number > 0.0)) value.fail("must be > 0 (got " + format_number(number) + ")");
  return number;
}

double read_non_negative(const JsonValue& value) {
  const double number = value.number();
  if (number < 0.0) value.fail("must be >= 0 (got " + format_number(number) + ")");
  return number;
}

// The cone's full angle A and its soft edge P: 0 < A < 180, P >= 0, A/2 + P <= 90.
void read_cone(const JsonObject& object, Light& light) {
  const JsonValue cone = object.at("cone_angle_deg");
  light.cone_angle_deg = cone.number();
  if (!(light.cone_angle_deg > 0.0 && light.cone_angle_deg < 180.0))
    cone.fail("must be in (0, 180) degrees (got " + format_number(light.cone_angle_deg) + ")");
  if (auto penumbra = object.find("penumbra_angle_deg")) {
    light.penumbra_angle_deg = penumbra->number();
    if (light.penumbra_angle_deg < 0.0)
      penumbra->fail("must be >= 0 degrees (got " + format_number(light.penumbra_angle_deg) + ")");
    if (light.cone_angle_deg / 2.0 + light.penumbra_angle_deg > 90.0)
      penumbra->fail("must keep cone_angle_deg/2 + penumbra_angle_deg <= 90 (got " +
                     format_number(light.cone_angle_deg / 2.0 + light.penumbra_angle_deg) + ")");
  }
}

std::vector<int> read_linked_materials(const JsonValue& value, std::size_t material_count) {
  std::vector<int> materials;
  for (const JsonValue& element : value.elements()) {
    const int index = element.integer();
    if (index < 0 || static_cast<std::size_t>(index) >= material_count)
      element.fail("material index " + std::to_string(index) + " is out of range (the scene has " +
                   std::to_string(material_count) + " materials)");
    materials.push_back(index);
  }
  return materials;
}

Light read_light(const JsonValue& value, std::size_t material_count) {
  const JsonObject object = value.object();
  object.expect_keys({"type", "position", "direction", "color", "falloff", "range", "cone_angle_deg",
                      "penumbra_angle_deg", "cosine_power", "materials", "shadows", "radius", "angle",
                      "shadow_rays", "group"});
  const std::string type = object.at("type").string();
  Light light;
  if (type == "point" || type == "spot") {
    light.type = type == "point" ? LightType::point : LightType::spot;
    light.position = object.at("position").vec3();
    if (auto falloff = object.find("falloff")) light.falloff = read_falloff(*falloff);
    if (auto range = object.find("range")) light.range = read_positive(*range);
    if (auto radius = object.find("radius")) light.radius = read_non_negative(*radius);
    if (object.has("angle")) object.at("angle").fail("is used only by directional lights (a point or spot takes 'radius')");
  } else if (type == "directional") {
    light.type = LightType::directional;
    if (object.has("position")) object.at("position").fail("is not used by a directional light (use 'direction')");
    for (const char* key : {"falloff", "range", "radius"})
      if (object.has(key)) object.at(key).fail("is not used by a directional light (it has no distance)");
    if (auto angle = object.find("angle")) {
      light.angle_deg = angle->number();
      if (!(light.angle_deg >= 0.0 && light.angle_deg < 180.0))
        angle->fail("must be in [0, 180) degrees (got " + format_number(light.angle_deg) + ")");
    }
  } else {
    throw InputError(value.file(), "unknown light type '" + type + "' in " + value.place() +
                                       " (expected point, spot, directional or area)");
  }
  if (light.type == LightType::point) {
    if (object.has("direction")) object.at("direction").fail("is not used by a point light (use 'position')");
  } else {
    const JsonValue direction = object.at("direction");
    light.direction = direction.vec3();
    if (light.direction == glm::dvec3(0.0)) direction.fail("must not be zero");
  }
  if (light.type == LightType::spot) {
    read_cone(object, light);
    if (auto power = object.find("cosine_power")) light.cosine_power = read_non_negative(*power);
  } else {
    for (const char* key : {"cone_angle_deg", "penumbra_angle_deg", "cosine_power"})
      if (object.has(key)) object.at(key).fail("is used only by spot lights");
  }
  if (auto color = object.find("color")) light.color = read_non_negative_vec3(*color);
  if (auto materials = object.find("materials")) light.materials = read_linked_materials(*materials, material_count);
  if (auto shadows = object.find("shadows")) light.shadows = shadows->boolean();
  if (auto rays = object.find("shadow_rays")) light.shadow_rays = read_shadow_rays(*rays);
  if (auto group = object.find("group")) {
    light.group = group->string();
    if (!valid_light_group_name(light.group)) group->fail(kLightGroupNameRule);
  }
  return light;
}

// A number in [low, high], else the field's one-line error.
double read_number_in(const JsonValue& value, double low, double high) {
  const double number = value.number();
  if (!(number >= low && number <= high))
    value.fail("must be in [" + format_number(low) + ", " + format_number(high) + "] (got " + format_number(number) + ")");
  return number;
}

// The Principled model's fields, refused on other models; its Phong coefficients refused on it; each
// version's own inputs refused on the other (specular_tint is a number in version 1, a colour in 2).
void read_principled_fields(const JsonObject& object, Material& material) {
  const bool principled = material.specular_model == SpecularModel::principled;
  for (const char* key : {"base_color", "metallic", "roughness", "specular", "specular_tint", "version", "ior",
                          "specular_ior_level", "diffuse_roughness"})
    if (!principled && object.has(key)) object.at(key).fail("is used only by specular_model \"principled\"");
  for (const char* key : {"kd", "ks", "shininess"})
    if (principled && object.has(key)) object.at(key).fail("is not used by specular_model \"principled\" (base_color, metallic, specular are)");
  if (!principled) return;
  if (auto version = object.find("version")) {
    if (version->number() != 1.0 && version->number() != 2.0)
      version->fail("must be 1 (the Principled BSDF of Blender 2.8 to 3.6) or 2 (Blender 4.0 on)");
    material.version = static_cast<int>(version->number());
  }
  const bool v2 = material.version == 2;
  if (v2 && object.has("specular")) object.at("specular").fail("is version 1's input (version 2 has ior and specular_ior_level)");
  for (const char* key : {"ior", "specular_ior_level", "diffuse_roughness"})
    if (!v2 && object.has(key)) object.at(key).fail("is version 2's input (set \"version\": 2)");
  if (auto color = object.find("base_color")) material.base_color = read_non_negative_vec3(*color);
  if (auto metallic = object.find("metallic")) material.metallic = read_number_in(*metallic, 0.0, 1.0);
  if (auto roughness = object.find("roughness")) material.roughness = read_number_in(*roughness, 0.0, 1.0);
  if (auto specular = object.find("specular")) material.specular = read_number_in(*specular, 0.0, 12.0);
  if (auto tint = object.find("specular_tint")) {
    if (v2) material.specular_tint_color = read_non_negative_vec3(*tint);
    else material.specular_tint = read_number_in(*tint, 0.0, 1.0);
  }
  if (auto ior = object.find("ior")) material.ior = read_number_in(*ior, 1.0, 1000.0);
  if (auto level = object.find("specular_ior_level")) material.specular_ior_level = read_number_in(*level, 0.0, 1000.0);
  if (auto roughness = object.find("diffuse_roughness")) material.diffuse_roughness = read_number_in(*roughness, 0.0, 1.0);
}

Material read_material(const JsonValue& value) {
  const JsonObject object = value.object();
  object.expect_keys({"name", "ka", "kd", "ks", "shininess", "specular_model", "base_color", "metallic", "roughness",
                      "specular", "specular_tint", "version", "ior", "specular_ior_level", "diffuse_roughness"});
  Material material;
  if (auto name = object.find("name")) material.name = name->string();
  if (auto ka = object.find("ka")) material.ka = read_non_negative_vec3(*ka);
  if (auto kd = object.find("kd")) material.kd = read_non_negative_vec3(*kd);
  if (auto ks = object.find("ks")) material.ks = read_non_negative_vec3(*ks);
  if (auto shininess = object.find("shininess")) {
    material.shininess = shininess->number();
    if (material.shininess < 0.0)
      shininess->fail("must be >= 0 (got " + format_number(material.shininess) + ")");
  }
  if (auto model = object.find("specular_model")) {
    try {
      material.specular_model = parse_specular_model(model->string());
    } catch (const std::invalid_argument& unknown) {
      model->fail(unknown.what());
    }
  }
  read_principled_fields(object, material);
  return material;
}

bool is_area_light(const JsonValue& value) {
  const JsonObject object = value.object();
  return object.has("type") && object.at("type").string() == "area";
}

std::filesystem::path read_gbuffer_path(const JsonValue& value, const std::filesystem::path& source) {
  const std::filesystem::path path = value.string();
  if (path.empty()) value.fail("must not be empty");
  return path.is_absolute() ? path : source.parent_path() / path;
}

// At most one environment: two worlds have no meaning a renderer agrees on (Blender has one).
void read_lights(const JsonValue& list, std::size_t material_count, std::vector<Light>& lights,
                 std::vector<AreaLight>& area_lights, std::optional<EnvironmentLight>& environment) {
  for (const JsonValue& light : list.elements()) {
    if (is_area_light(light)) {
      area_lights.push_back(read_area_light(light.object()));
    } else if (is_environment_light(light)) {
      if (environment) light.fail("is a second environment light (a scene has at most one world)");
      environment = read_environment_light(light.object(), list.file());
    } else {
      lights.push_back(read_light(light, material_count));
    }
  }
}

}  // namespace

Scene parse_scene(std::string_view json_text, const std::filesystem::path& source) {
  return read_scene(parse_json(json_text, source), source);
}

Scene read_scene(const nlohmann::json& document, const std::filesystem::path& source) {
  const JsonObject top = JsonValue(document, "", source).object();
  top.expect_keys({"camera", "background", "ambient", "lights", "materials", "objects", "gbuffer", "color_space", "rendered"});
  Scene scene;
  scene.source = source;
  if (auto value = top.find("camera")) scene.camera = read_camera(value->object());
  else scene.has_camera = false;
  if (auto value = top.find("background")) scene.background = read_non_negative_vec3(*value);
  if (auto value = top.find("ambient")) scene.ambient = read_non_negative_vec3(*value);
  if (auto value = top.find("materials"))
    for (const JsonValue& material : value->elements()) scene.materials.push_back(read_material(material));
  // After materials: lights (linking) and objects refer to them by index.
  if (auto value = top.find("lights")) read_lights(*value, scene.materials.size(), scene.lights, scene.area_lights, scene.environment);
  if (auto value = top.find("rendered")) {
    const JsonObject rendered = value->object();
    rendered.expect_keys({"lights"});
    scene.rendered.emplace();
    read_lights(rendered.at("lights"), scene.materials.size(), scene.rendered->lights, scene.rendered->area_lights,
                scene.rendered->environment);
  }
  if (auto value = top.find("objects")) scene.objects = read_objects(*value, scene.materials.size());
  if (auto value = top.find("gbuffer")) scene.gbuffer = read_gbuffer_path(*value, source);
  if (auto value = top.find("color_space")) {
    scene.color_space = value->string();
    if (scene.color_space.empty()) value->fail("must name a colour space (leave it out for the working space)");
  }
  return scene;
}

const char* to_string(Falloff falloff) {
  switch (falloff) {
    case Falloff::none: return "none";
    case Falloff::linear: return "linear";
    case Falloff::quadratic: return "quadratic";
    case Falloff::cubic: return "cubic";
  }
  return "none";
}

const char* to_string(SpecularModel model) {
  switch (model) {
    case SpecularModel::phong: return "phong";
    case SpecularModel::phong_normalized: return "phong-normalized";
    case SpecularModel::blinn_phong: return "blinn-phong";
    case SpecularModel::blinn_phong_normalized: return "blinn-phong-normalized";
    case SpecularModel::principled: return "principled";
  }
  return "phong";
}

SpecularModel parse_specular_model(const std::string& name) {
  for (SpecularModel model : kSpecularModels)
    if (name == to_string(model)) return model;
  if (name == to_string(SpecularModel::principled)) return SpecularModel::principled;
  throw std::invalid_argument("'" + name + "' is not a specular model (expected phong, phong-normalized, blinn-phong, " +
                              "blinn-phong-normalized or principled)");
}

std::vector<std::string> light_groups(const std::vector<Light>& lights, const std::vector<AreaLight>& area_lights,
                                      const std::optional<EnvironmentLight>& environment) {
  std::vector<std::string> names;
  auto add = [&](const std::string& group) {
    if (!group.empty() && std::find(names.begin(), names.end(), group) == names.end()) names.push_back(group);
  };
  for (const Light& light : lights) add(light.group);
  for (const AreaLight& light : area_lights) add(light.group);
  if (environment) add(environment->group);
  return names;
}

bool Light::reaches(int material) const {
  return !materials || std::find(materials->begin(), materials->end(), material) != materials->end();
}

Scene load_scene(const std::filesystem::path& file) {
  std::error_code ignored;
  if (std::filesystem::is_directory(file, ignored)) throw InputError(file, "cannot open (a directory)");
  std::ifstream stream(file, std::ios::binary);
  if (!stream) throw InputError(file, "cannot open");
  std::ostringstream text;
  text << stream.rdbuf();
  if (stream.bad()) throw InputError(file, "cannot read");
  return parse_scene(text.str(), file);
}

std::vector<Light> parse_lights(std::string_view json_text, const std::filesystem::path& source,
                                std::size_t material_count) {
  return read_lights(parse_json(json_text, source), source, material_count);
}

std::vector<Material> parse_materials(std::string_view json_text, const std::filesystem::path& source) {
  return read_materials(parse_json(json_text, source), source);
}

std::vector<Light> read_lights(const nlohmann::json& document, const std::filesystem::path& source,
                               std::size_t material_count) {
  std::vector<Light> lights;
  for (const JsonValue& light : JsonValue(document, "lights", source).elements()) {
    if (is_area_light(light)) light.fail("is an area light: set_area_lights takes those");
    if (is_environment_light(light)) light.fail("is an environment light: set_environment takes it");
    lights.push_back(read_light(light, material_count));
  }
  return lights;
}

std::vector<AreaLight> read_area_lights(const nlohmann::json& document, const std::filesystem::path& source) {
  std::vector<AreaLight> lights;
  for (const JsonValue& light : JsonValue(document, "area_lights", source).elements()) {
    if (!is_area_light(light)) light.fail("is not an area light (\"type\": \"area\"): set_lights takes those");
    lights.push_back(read_area_light(light.object()));
  }
  return lights;
}

std::vector<Material> read_materials(const nlohmann::json& document, const std::filesystem::path& source) {
  std::vector<Material> materials;
  for (const JsonValue& material : JsonValue(document, "materials", source).elements())
    materials.push_back(read_material(material));
  return materials;
}

}  // namespace phongcl
