// Scene files: the bundled scenes, defaults, path resolution, every validation error, and the
// conversion of transforms to GLM's column-major matrices.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "common/error.h"
#include "scene/area_light_json.h"
#include "scene/camera_space.h"
#include "scene/scene.h"
#include "scene/scene_check.h"

namespace phongcl {
namespace {

const std::filesystem::path kDefaultScene = PHONGCL_SOURCE_DIR "/scenes/default/scene.json";
const std::filesystem::path kSource = "some/dir/scene.json";

// A valid scene with one material, plus `extra` top-level entries; `camera` replaces the camera.
std::string scene_json(const std::string& extra, const std::string& camera = R"({"eye": [0, 0, 5]})") {
  std::string text = R"({"camera": )" + camera + R"(, "materials": [{"kd": [1, 1, 1]}])";
  return text + (extra.empty() ? "" : ", " + extra) + "}";
}

// The InputError message for `json`, or a test failure if it parses.
std::string error_of(const std::string& json) {
  try {
    parse_scene(json, kSource);
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "parsed without error: " << json;
  return "";
}

TEST(Scene, BundledScenesParse) {
  for (const char* name : {"default", "shininess", "large", "directional_diffuse", "spotlights", "many_lights"}) {
    SCOPED_TRACE(name);
    const std::filesystem::path file = std::filesystem::path(PHONGCL_SOURCE_DIR) / "scenes" / name / "scene.json";
    const Scene scene = load_scene(file);
    EXPECT_EQ(scene.source, file);
    EXPECT_EQ(scene.gbuffer, file.parent_path() / "gbuffer.exr");
    EXPECT_FALSE(scene.lights.empty());
    EXPECT_FALSE(scene.materials.empty());
    EXPECT_FALSE(scene.objects.empty());
  }
}

TEST(Scene, BundledScenesHaveTheirPurpose) {
  const std::filesystem::path scenes = std::filesystem::path(PHONGCL_SOURCE_DIR) / "scenes";

  const Scene shininess = load_scene(scenes / "shininess" / "scene.json");
  ASSERT_EQ(shininess.materials.size(), 6u);
  const double exponents[] = {1, 4, 16, 64, 256, 1024};
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(shininess.materials[i].shininess, exponents[i]);

  const Scene large = load_scene(scenes / "large" / "scene.json");
  EXPECT_EQ(large.camera.width, 1920);
  EXPECT_EQ(large.camera.height, 1080);
  EXPECT_GE(large.objects.size(), 100u);
  int point_lights = 0;
  for (const Light& light : large.lights) point_lights += light.type == LightType::point;
  EXPECT_EQ(point_lights, 3);
  EXPECT_EQ(large.lights.size(), 5u);

  // The classic figure: soft-edged spots with falloff; and thousands of ranged lights over the large
  // scene's objects, which culling is for.
  const Scene spots = load_scene(scenes / "spotlights" / "scene.json");
  int spot_lights = 0;
  for (const Light& light : spots.lights) spot_lights += light.type == LightType::spot && light.penumbra_angle_deg > 0;
  EXPECT_GE(spot_lights, 3);
  const Scene many = load_scene(scenes / "many_lights" / "scene.json");
  EXPECT_GE(many.lights.size(), 1000u);
  for (const Light& light : many.lights) EXPECT_TRUE(light.has_range());
  EXPECT_EQ(many.objects.size(), large.objects.size());

  // The scene that shows the kernel with the specular path compiled out.
  const Scene diffuse = load_scene(scenes / "directional_diffuse" / "scene.json");
  for (const Light& light : diffuse.lights) EXPECT_EQ(light.type, LightType::directional);
  for (const Material& material : diffuse.materials) EXPECT_EQ(material.ks, glm::dvec3(0.0)) << material.name;
}

TEST(Scene, DefaultsFillEverythingButTheEye) {
  const Scene scene = parse_scene(R"({"camera": {"eye": [1, 2, 3]}})", kSource);
  const Camera defaults;
  EXPECT_EQ(scene.camera.eye, glm::dvec3(1, 2, 3));
  EXPECT_EQ(scene.camera.look_at, defaults.look_at);
  EXPECT_EQ(scene.camera.up, defaults.up);
  EXPECT_EQ(scene.camera.fov_y_deg, defaults.fov_y_deg);
  EXPECT_EQ(scene.camera.width, defaults.width);
  EXPECT_EQ(scene.camera.height, defaults.height);
  EXPECT_EQ(scene.background, glm::dvec3(0.0));
  EXPECT_EQ(scene.ambient, glm::dvec3(0.0));
  EXPECT_TRUE(scene.lights.empty());
  EXPECT_TRUE(scene.materials.empty());
  EXPECT_TRUE(scene.objects.empty());
  EXPECT_TRUE(scene.gbuffer.empty());
  EXPECT_EQ(scene.source, kSource);
}

TEST(Scene, EntryDefaults) {
  const Scene scene = parse_scene(scene_json(R"(
      "lights": [{"type": "point", "position": [1, 2, 3]}],
      "objects": [{"type": "sphere"}, {"type": "plane"}, {"type": "transform"}])"),
                                  kSource);
  EXPECT_EQ(scene.lights.at(0).color, glm::dvec3(1.0));
  EXPECT_EQ(scene.materials.at(0).name, "");
  EXPECT_EQ(scene.materials.at(0).ka, glm::dvec3(0.0));
  EXPECT_EQ(scene.materials.at(0).shininess, Material{}.shininess);
  EXPECT_EQ(scene.materials.at(0).specular_model, SpecularModel::phong);
  EXPECT_EQ(scene.objects.at(0).radius, 1.0);
  EXPECT_EQ(scene.objects.at(0).material, 0);
  EXPECT_EQ(scene.objects.at(1).normal, glm::dvec3(0, 1, 0));
  EXPECT_EQ(scene.objects.at(2).matrix, glm::dmat4(1.0));
}

TEST(Scene, ReadsEveryField) {
  const Scene scene = parse_scene(R"({
    "camera": {"eye": [0, 1, 6], "look_at": [0, 0.5, 0], "up": [0, 0, 1], "fov_y_deg": 60, "width": 32, "height": 16},
    "background": [0.1, 0.2, 0.3], "ambient": [0.4, 0.5, 0.6],
    "lights": [{"type": "directional", "direction": [-1, -1, -1], "color": [2, 3, 4]}],
    "materials": [{"name": "m", "ka": [0.1, 0, 0], "kd": [0, 0.2, 0], "ks": [0, 0, 0.3], "shininess": 0}],
    "objects": [{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]},
                {"type": "plane", "normal": [0, 0, 2], "offset": -1}]})",
                                  kSource);
  EXPECT_EQ(scene.camera.look_at, glm::dvec3(0, 0.5, 0));
  EXPECT_EQ(scene.camera.up, glm::dvec3(0, 0, 1));
  EXPECT_EQ(scene.camera.fov_y_deg, 60.0);
  EXPECT_EQ(scene.camera.width, 32);
  EXPECT_EQ(scene.camera.height, 16);
  EXPECT_EQ(scene.background, glm::dvec3(0.1, 0.2, 0.3));
  EXPECT_EQ(scene.ambient, glm::dvec3(0.4, 0.5, 0.6));
  EXPECT_EQ(scene.lights.at(0).type, LightType::directional);
  EXPECT_EQ(scene.lights.at(0).direction, glm::dvec3(-1, -1, -1));
  EXPECT_EQ(scene.lights.at(0).color, glm::dvec3(2, 3, 4));
  EXPECT_EQ(scene.materials.at(0).name, "m");
  EXPECT_EQ(scene.materials.at(0).ks, glm::dvec3(0, 0, 0.3));
  EXPECT_EQ(scene.materials.at(0).shininess, 0.0);  // zero is allowed: a flat specular term
  EXPECT_EQ(scene.objects.at(0).kind, Object::Kind::triangle);
  EXPECT_EQ(scene.objects.at(0).vertices[1], glm::dvec3(1, 0, 0));
  EXPECT_EQ(scene.objects.at(1).offset, -1.0);
}

TEST(Scene, ReadsEverySpecularModelByName) {
  for (SpecularModel model : kSpecularModels) {
    const std::string name = to_string(model);
    const Scene scene = parse_scene(R"({"materials": [{"ks": [1, 1, 1], "specular_model": ")" + name + R"("}]})", kSource);
    EXPECT_EQ(scene.materials.at(0).specular_model, model) << name;
    EXPECT_EQ(parse_specular_model(name), model);
  }
}

TEST(Scene, ReadsTheLightShapes) {
  const Scene scene = parse_scene(scene_json(R"(
      "lights": [{"type": "spot", "position": [1, 2, 3], "direction": [0, -1, 0], "cone_angle_deg": 40,
                  "penumbra_angle_deg": 10, "falloff": "quadratic", "range": 7.5, "materials": [0]},
                 {"type": "point", "position": [0, 0, 0], "falloff": "cubic"},
                 {"type": "spot", "position": [0, 0, 0], "direction": [0, 0, 1], "cone_angle_deg": 30, "cosine_power": 1.5},
                 {"type": "directional", "direction": [0, 0, -1], "materials": []}])"),
                                  kSource);
  const Light& spot = scene.lights.at(0);
  EXPECT_EQ(spot.type, LightType::spot);
  EXPECT_EQ(spot.direction, glm::dvec3(0, -1, 0));
  EXPECT_EQ(spot.cone_angle_deg, 40.0);
  EXPECT_EQ(spot.penumbra_angle_deg, 10.0);
  EXPECT_EQ(spot.falloff, Falloff::quadratic);
  EXPECT_EQ(spot.range, 7.5);
  EXPECT_EQ(spot.cosine_power, 0.0) << "no 'cosine_power': today's cone";
  EXPECT_TRUE(spot.reaches(0));
  const Light& point = scene.lights.at(1);
  EXPECT_EQ(point.falloff, Falloff::cubic);
  EXPECT_FALSE(point.has_range());
  EXPECT_TRUE(point.reaches(0)) << "no 'materials': every material";
  EXPECT_EQ(scene.lights.at(2).cosine_power, 1.5);
  EXPECT_FALSE(scene.lights.at(3).reaches(0)) << "'materials': [] lights none";
}

TEST(Scene, AreaLightsGoToTheirOwnTable) {
  const Scene scene = parse_scene(scene_json(R"(
      "lights": [{"type": "point", "position": [0, 0, 0]},
                 {"type": "area", "shape": "rect", "position": [1, 2, 3], "direction": [0, -2, 0], "up": [0, 0, 1],
                  "size": [2, 0.5], "color": [3, 2, 1], "range": 9},
                 {"type": "area", "shape": "disk", "position": [0, 4, 0], "direction": [0, 0, -1], "size": 0.25,
                  "group": "fill", "shadows": true}])"),
                                  kSource);
  ASSERT_EQ(scene.lights.size(), 1u) << "area lights are not point, spot or directional lights";
  ASSERT_EQ(scene.area_lights.size(), 2u);
  const AreaLight& rect = scene.area_lights[0];
  EXPECT_EQ(rect.shape, AreaShape::rect);
  EXPECT_EQ(rect.position, glm::dvec3(1, 2, 3));
  EXPECT_EQ(rect.direction, glm::dvec3(0, -2, 0));
  EXPECT_EQ(rect.up, glm::dvec3(0, 0, 1));
  EXPECT_EQ(rect.size, glm::dvec2(2, 0.5));
  EXPECT_EQ(rect.color, glm::dvec3(3, 2, 1));
  EXPECT_EQ(rect.range, 9.0);
  EXPECT_FALSE(rect.shadows);
  EXPECT_TRUE(rect.group.empty());
  const AreaLight& disk = scene.area_lights[1];
  EXPECT_EQ(disk.shape, AreaShape::disk);
  EXPECT_EQ(disk.size, glm::dvec2(0.25, 0.25));
  EXPECT_EQ(disk.color, glm::dvec3(1.0));
  EXPECT_FALSE(disk.has_range());
  EXPECT_TRUE(disk.shadows);
  EXPECT_EQ(disk.group, "fill");
  EXPECT_EQ(light_groups(scene.lights, scene.area_lights), std::vector<std::string>{"fill"});
  EXPECT_THROW(parse_lights(R"([{"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, -1], "size": 1}])",
                            kSource),
               InputError);
}

TEST(Scene, HdrValuesUpToFloatRangeParse) {
  const Scene scene = parse_scene(scene_json(R"(
      "ambient": [3e38, 0, 0],
      "lights": [{"type": "point", "position": [0, 0, 0], "color": [3e38, 1e6, 0]}])"),
                                  kSource);
  EXPECT_EQ(scene.ambient.x, 3e38);
  EXPECT_EQ(scene.lights.at(0).color.x, 3e38);
}

// The kernel forms an area light's area and its axes' squared lengths in float: a rect of
// 1e20 x 1e20 shaded to NaN. The reader and the check for lights built in code refuse any size
// past 1e18, where those products stay far below float's largest value.
TEST(Scene, AreaLightSizesStayWhereTheirSquaresFitFloat) {
  const std::string rect = R"({"type": "area", "shape": "rect", "position": [0, 0, 0], "direction": [0, 0, -1], "size": )";
  const std::string disk = R"({"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, -1], "size": )";
  auto with_light = [](const std::string& light) { return scene_json(R"("lights": [)" + light + "}]"); };
  EXPECT_EQ(parse_scene(with_light(rect + "[1e18, 1e18]"), kSource).area_lights.at(0).size, glm::dvec2(1e18));
  EXPECT_EQ(parse_scene(with_light(disk + "1e18"), kSource).area_lights.at(0).size, glm::dvec2(1e18));
  const std::vector<std::pair<std::string, std::string>> refused = {
      {rect + "[1e20, 1]", "lights[0].size[0] must be at most 1e+18 (got 1e+20)"},
      {rect + "[1, 2e18]", "lights[0].size[1] must be at most 1e+18 (got 2e+18)"},
      {disk + "1e20", "lights[0].size must be at most 1e+18 (got 1e+20)"},
  };
  for (const auto& [light, expected] : refused) {
    const std::string message = error_of(with_light(light));
    EXPECT_NE(message.find(expected), std::string::npos) << "message: " << message << "\nexpected: " << expected;
  }
  AreaLight huge;
  huge.size = glm::dvec2(1e20);
  try {
    check_area_lights({AreaLight{}, huge});
    ADD_FAILURE() << "a rect of 1e20 x 1e20 built in code was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("area_lights[1].size: must be at most 1e+18"), std::string::npos) << error.what();
  }
}

// A light group names the EXR channels group.<name>.R/G/B, which OpenEXR cuts at 255 bytes (a
// long name's R, G and B became one channel); the rule takes Blender's 63 bytes.
TEST(Scene, LightGroupNamesHoldAtMost63Bytes) {
  const std::string longest(63, 'g'), too_long(64, 'g');
  auto with_group = [](const std::string& group) {
    return scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "group": ")" + group + R"("},
        {"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, -1], "size": 1, "group": ")" +
                      group + R"("}])");
  };
  const Scene scene = parse_scene(with_group(longest), kSource);
  EXPECT_EQ(scene.lights.at(0).group, longest);
  EXPECT_EQ(scene.area_lights.at(0).group, longest);
  const std::string message = error_of(with_group(too_long));
  EXPECT_NE(message.find("lights[0].group must be"), std::string::npos) << message;
  EXPECT_NE(message.find("63 bytes"), std::string::npos) << "the message states the limit: " << message;
  Light point;
  point.group = too_long;
  EXPECT_THROW(check_lights({point}, 1), std::invalid_argument);
  AreaLight area;
  area.group = too_long;
  EXPECT_THROW(check_area_lights({area}), std::invalid_argument);
}

TEST(Scene, GbufferPathIsRelativeToTheSceneFile) {
  EXPECT_EQ(parse_scene(scene_json(R"("gbuffer": "g.exr")"), "some/dir/scene.json").gbuffer,
            std::filesystem::path("some/dir/g.exr"));
  EXPECT_EQ(parse_scene(scene_json(R"("gbuffer": "../g/b.exr")"), "/abs/scene.json").gbuffer,
            std::filesystem::path("/abs/../g/b.exr"));
  EXPECT_EQ(parse_scene(scene_json(R"("gbuffer": "g.exr")"), "scene.json").gbuffer, std::filesystem::path("g.exr"));
  EXPECT_EQ(parse_scene(scene_json(R"("gbuffer": "/elsewhere/g.exr")"), kSource).gbuffer,
            std::filesystem::path("/elsewhere/g.exr"));
}

struct ErrorCase {
  const char* what;
  std::string json;
  std::vector<std::string> expected;  // substrings of the message
};

TEST(Scene, EachProblemIsAOneLineInputErrorNamingFileAndPlace) {
  const std::string point = R"({"type": "point", "position": [0, 0, 0]})";
  const std::vector<ErrorCase> cases = {
      {"unknown key in a light",
       scene_json(R"("lights": [)" + point + R"(, {"type": "point", "position": [1, 1, 1], "colour": [1, 1, 1]}])"),
       {"unknown key 'colour' in lights[1] (expected: type, position, direction, color, falloff, range"}},
      {"unknown key at the top level", scene_json(R"("lihgts": [])"), {"unknown key 'lihgts' in the top level"}},
      {"unknown key in the camera", scene_json("", R"({"eye": [0, 0, 5], "fov": 30})"),
       {"unknown key 'fov' in camera (expected: eye, look_at"}},
      {"unknown key in a material", scene_json("").replace(scene_json("").find("\"kd\""), 4, "\"Kd\""),
       {"unknown key 'Kd' in materials[0]"}},
      {"unknown key in an object", scene_json(R"("objects": [{"type": "sphere", "radius": 1, "offset": 2}])"),
       {"unknown key 'offset' in objects[0] (expected: type, center, radius, material)"}},
      {"unknown key in a nested object",
       scene_json(R"("objects": [{"type": "transform", "children": [{"type": "plane", "colour": 1}]}])"),
       {"unknown key 'colour' in objects[0].children[0]"}},
      {"missing eye", scene_json("", R"({"look_at": [0, 0, 0]})"), {"missing key 'eye' in camera"}},
      {"wrong type", scene_json("", R"({"eye": "far away"})"), {"camera.eye must be an array of 3 numbers"}},
      {"wrong length", scene_json("", R"({"eye": [0, 0]})"), {"camera.eye must be an array of 3 numbers"}},
      {"string where a number goes", scene_json(R"("ambient": [0, "0", 0])"), {"ambient[1] must be a number"}},
      {"fractional size", scene_json("", R"({"eye": [0, 0, 5], "width": 1.5})"), {"camera.width must be an integer"}},
      {"name not a string", scene_json("").replace(scene_json("").find("{\"kd\""), 1, "{\"name\": 7, "),
       {"materials[0].name must be a string"}},
      {"lights not an array", scene_json(R"("lights": {})"), {"lights must be an array"}},
      {"light not an object", scene_json(R"("lights": [3])"), {"lights[0] must be an object"}},
      {"number beyond float range", scene_json(R"("ambient": [1e39, 0, 0])"),
       {"ambient[0] must be a finite single-precision number"}},
      {"number beyond double range", scene_json(R"("ambient": [1e999, 0, 0])"), {"invalid JSON", "1e999"}},
      {"unknown light type", scene_json(R"("lights": [{"type": "mesh", "position": [0, 0, 0]}])"),
       {"unknown light type 'mesh' in lights[0] (expected point, spot, directional or area)"}},
      {"area light without a shape", scene_json(R"("lights": [{"type": "area", "position": [0, 0, 0]}])"),
       {"missing key 'shape' in lights[0]"}},
      {"unknown area shape", scene_json(R"("lights": [{"type": "area", "shape": "ellipse", "position": [0, 0, 0], "direction": [0, 0, -1], "size": 1}])"),
       {"lights[0].shape 'ellipse' is not an area light shape (expected rect or disk)"}},
      {"zero area size", scene_json(R"("lights": [{"type": "area", "shape": "rect", "position": [0, 0, 0], "direction": [0, 0, -1], "size": [1, 0]}])"),
       {"lights[0].size[1] must be finite and > 0 (got 0)"}},
      {"negative disk size", scene_json(R"("lights": [{"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, -1], "size": -2}])"),
       {"lights[0].size must be finite and > 0 (got -2)"}},
      {"rect size not a pair", scene_json(R"("lights": [{"type": "area", "shape": "rect", "position": [0, 0, 0], "direction": [0, 0, -1], "size": [1, 2, 3]}])"),
       {"lights[0].size must be [width, height] for a rect"}},
      {"zero area direction", scene_json(R"("lights": [{"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, 0], "size": 1}])"),
       {"lights[0].direction must not be zero"}},
      {"up parallel to direction", scene_json(R"("lights": [{"type": "area", "shape": "rect", "position": [0, 0, 0], "direction": [0, 0, -1], "up": [0, 0, 2], "size": [1, 1]}])"),
       {"lights[0].up must not be zero or parallel to direction"}},
      {"direction along the default up", scene_json(R"("lights": [{"type": "area", "shape": "rect", "position": [0, 0, 0], "direction": [0, -1, 0], "size": [1, 1]}])"),
       {"lights[0].direction is parallel to the default up (0, 1, 0): give 'up'"}},
      {"up on a disk", scene_json(R"("lights": [{"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, -1], "up": [0, 1, 0], "size": 1}])"),
       {"lights[0].up is used only by rect area lights"}},
      {"falloff on an area light", scene_json(R"("lights": [{"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, -1], "size": 1, "falloff": "quadratic"}])"),
       {"unknown key 'falloff' in lights[0] (expected: type, shape, position, direction, up, size, color, range, shadows, shadow_rays, group)"}},
      {"no shadow rays", scene_json(R"("lights": [{"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, -1], "size": 1, "shadow_rays": 0}])"),
       {"lights[0].shadow_rays must be a whole number from 1 to 1024 (got 0)"}},
      {"too many shadow rays", scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "radius": 0.1, "shadow_rays": 5000}])"),
       {"lights[0].shadow_rays must be a whole number from 1 to 1024 (got 5000)"}},
      {"negative light radius", scene_json(R"("lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, 0, -1], "cone_angle_deg": 30, "radius": -0.25}])"),
       {"lights[0].radius must be >= 0 (got -0.25)"}},
      {"radius on a sun", scene_json(R"("lights": [{"type": "directional", "direction": [0, 0, -1], "radius": 1}])"),
       {"lights[0].radius is not used by a directional light"}},
      {"sun angle out of range", scene_json(R"("lights": [{"type": "directional", "direction": [0, 0, -1], "angle": 180}])"),
       {"lights[0].angle must be in [0, 180) degrees (got 180)"}},
      {"angle on a point light", scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "angle": 1}])"),
       {"lights[0].angle is used only by directional lights"}},
      {"bad group on an area light", scene_json(R"("lights": [{"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, -1], "size": 1, "group": "a b"}])"),
       {"lights[0].group must be a name of letters, digits, '_' and '-'"}},
      {"shadows on an area light not a boolean", scene_json(R"("lights": [{"type": "area", "shape": "disk", "position": [0, 0, 0], "direction": [0, 0, -1], "size": 1, "shadows": 1}])"),
       {"lights[0].shadows"}},
      {"unknown specular model", scene_json("").replace(scene_json("").find("{\"kd\""), 1, "{\"specular_model\": \"blinn\", "),
       {"materials[0].specular_model 'blinn' is not a specular model (expected phong, phong-normalized, blinn-phong, "
        "blinn-phong-normalized or principled)"}},
      {"principled field on a Phong material", scene_json("").replace(scene_json("").find("{\"kd\""), 1, "{\"metallic\": 1, "),
       {"materials[0].metallic is used only by specular_model \"principled\""}},
      {"Phong field on a principled material",
       scene_json("").replace(scene_json("").find("{\"kd\""), 1, "{\"specular_model\": \"principled\", "),
       {"materials[0].kd is not used by specular_model \"principled\""}},
      {"principled roughness beyond 1",
       R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"specular_model": "principled", "roughness": 1.5}]})",
       {"materials[0].roughness must be in [0, 1] (got 1.5)"}},
      {"principled version 3",
       R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"specular_model": "principled", "version": 3}]})",
       {"materials[0].version must be 1", "or 2"}},
      {"principled version 1's specular on version 2",
       R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"specular_model": "principled", "version": 2, "specular": 0.5}]})",
       {"materials[0].specular is version 1's input"}},
      {"principled version 2's ior on version 1",
       R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"specular_model": "principled", "ior": 1.5}]})",
       {"materials[0].ior is version 2's input"}},
      {"principled version 2 below index 1",
       R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"specular_model": "principled", "version": 2, "ior": 0.5}]})",
       {"materials[0].ior must be in [1, 1000]"}},
      {"principled version 2 with a diffuse roughness above 1",
       R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"specular_model": "principled", "version": 2, "diffuse_roughness": 1.5}]})",
       {"materials[0].diffuse_roughness must be in [0, 1]"}},
      {"principled version 1 with a diffuse roughness",
       R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"specular_model": "principled", "diffuse_roughness": 0.5}]})",
       {"materials[0].diffuse_roughness is version 2's input"}},
      {"specular model not a string", scene_json("").replace(scene_json("").find("{\"kd\""), 1, "{\"specular_model\": 2, "),
       {"materials[0].specular_model must be a string"}},
      {"unknown falloff", scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "falloff": "inverse"}])"),
       {"lights[0].falloff 'inverse' is not a falloff (expected none, linear, quadratic or cubic)"}},
      {"zero range", scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "range": 0}])"),
       {"lights[0].range must be > 0 (got 0)"}},
      {"negative range", scene_json(R"("lights": [)" + point + R"(, {"type": "spot", "position": [0, 0, 0], "direction": [0, 0, 1], "cone_angle_deg": 30, "range": -1}])"),
       {"lights[1].range must be > 0 (got -1)"}},
      {"range on a directional light", scene_json(R"("lights": [{"type": "directional", "direction": [0, 0, 1], "range": 2}])"),
       {"lights[0].range is not used by a directional light"}},
      {"spot without a cone", scene_json(R"("lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, 0, 1]}])"),
       {"missing key 'cone_angle_deg' in lights[0]"}},
      {"spot without a direction", scene_json(R"("lights": [{"type": "spot", "position": [0, 0, 0], "cone_angle_deg": 30}])"),
       {"missing key 'direction' in lights[0]"}},
      {"zero cone", scene_json(R"("lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, 0, 1], "cone_angle_deg": 0}])"),
       {"lights[0].cone_angle_deg must be in (0, 180) degrees (got 0)"}},
      {"straight cone", scene_json(R"("lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, 0, 1], "cone_angle_deg": 180}])"),
       {"lights[0].cone_angle_deg must be in (0, 180) degrees (got 180)"}},
      {"negative penumbra", scene_json(R"("lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, 0, 1], "cone_angle_deg": 30, "penumbra_angle_deg": -1}])"),
       {"lights[0].penumbra_angle_deg must be >= 0 degrees (got -1)"}},
      {"penumbra past 90", scene_json(R"("lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, 0, 1], "cone_angle_deg": 120, "penumbra_angle_deg": 31}])"),
       {"lights[0].penumbra_angle_deg must keep cone_angle_deg/2 + penumbra_angle_deg <= 90 (got 91)"}},
      {"negative cosine power", scene_json(R"("lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, 0, 1], "cone_angle_deg": 30, "cosine_power": -1}])"),
       {"lights[0].cosine_power must be >= 0 (got -1)"}},
      {"NaN cosine power", scene_json(R"("lights": [{"type": "spot", "position": [0, 0, 0], "direction": [0, 0, 1], "cone_angle_deg": 30, "cosine_power": NaN}])"),
       {"invalid JSON"}},
      {"cosine power on a point light", scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "cosine_power": 1}])"),
       {"lights[0].cosine_power is used only by spot lights"}},
      {"cone on a point light", scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "cone_angle_deg": 30}])"),
       {"lights[0].cone_angle_deg is used only by spot lights"}},
      {"linked material out of range", scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "materials": [0, 1]}])"),
       {"lights[0].materials[1] material index 1 is out of range (the scene has 1 materials)"}},
      {"linked material not an integer", scene_json(R"("lights": [{"type": "directional", "direction": [0, 0, 1], "materials": [0.5]}])"),
       {"lights[0].materials[0] must be an integer"}},
      {"unknown object type", scene_json(R"("objects": [{"type": "cone"}])"), {"unknown object type 'cone' in objects[0]"}},
      {"object without type", scene_json(R"("objects": [{"radius": 1}])"), {"missing key 'type' in objects[0]"}},
      {"negative shininess", R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"shininess": -1}]})",
       {"materials[0].shininess must be >= 0 (got -1)"}},
      {"negative ka", R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"ka": [0, -0.5, 0]}]})",
       {"materials[0].ka[1] must be >= 0 (got -0.5)"}},
      {"negative kd", R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"kd": [-1, 0, 0]}]})", {"materials[0].kd[0] must be >= 0"}},
      {"negative ks", R"({"camera": {"eye": [0, 0, 5]}, "materials": [{"ks": [0, 0, -2]}]})", {"materials[0].ks[2] must be >= 0"}},
      {"negative light color", scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "color": [1, -1, 1]}])"),
       {"lights[0].color[1] must be >= 0"}},
      {"negative ambient", scene_json(R"("ambient": [0, 0, -0.1])"), {"ambient[2] must be >= 0"}},
      {"zero radius", scene_json(R"("objects": [{"type": "sphere", "radius": 0}])"), {"objects[0].radius must be > 0 (got 0)"}},
      {"negative radius", scene_json(R"("objects": [{"type": "sphere", "radius": -2}])"), {"objects[0].radius must be > 0"}},
      {"zero width", scene_json("", R"({"eye": [0, 0, 5], "width": 0})"), {"camera.width must be >= 1 (got 0)"}},
      {"negative height", scene_json("", R"({"eye": [0, 0, 5], "height": -4})"), {"camera.height must be >= 1"}},
      {"zero fov", scene_json("", R"({"eye": [0, 0, 5], "fov_y_deg": 0})"), {"camera.fov_y_deg must be in (0, 180)"}},
      {"straight fov", scene_json("", R"({"eye": [0, 0, 5], "fov_y_deg": 180})"), {"camera.fov_y_deg must be in (0, 180)"}},
      {"eye at look_at", scene_json("", R"({"eye": [0, 0, 0]})"), {"camera look_at must differ from eye"}},
      {"up along the view", scene_json("", R"({"eye": [0, 5, 0]})"), {"camera up must not be zero or parallel"}},
      {"point light without position", scene_json(R"("lights": [{"type": "point"}])"), {"missing key 'position' in lights[0]"}},
      {"point light with a direction",
       scene_json(R"("lights": [{"type": "point", "position": [0, 0, 0], "direction": [0, -1, 0]}])"),
       {"lights[0].direction is not used by a point light"}},
      {"directional light without direction", scene_json(R"("lights": [{"type": "directional"}])"),
       {"missing key 'direction' in lights[0]"}},
      {"directional light with zero direction", scene_json(R"("lights": [{"type": "directional", "direction": [0, 0, 0]}])"),
       {"lights[0].direction must not be zero"}},
      {"material index out of range", scene_json(R"("objects": [{"type": "sphere", "material": 1}])"),
       {"objects[0] material index 1 is out of range (the scene has 1 materials)"}},
      {"negative material index", scene_json(R"("objects": [{"type": "plane", "material": -1}])"),
       {"objects[0] material index -1 is out of range"}},
      {"default material with no materials", R"({"camera": {"eye": [0, 0, 5]}, "objects": [{"type": "sphere"}]})",
       {"objects[0] material index 0 is out of range (the scene has 0 materials)"}},
      {"nested material index out of range",
       scene_json(R"("objects": [{"type": "transform", "children": [{"type": "sphere", "material": 4}]}])"),
       {"objects[0].children[0] material index 4"}},
      {"singular matrix",
       scene_json(R"("objects": [{"type": "transform", "matrix": [1, 0, 0, 0,  0, 1, 0, 0,  1, 1, 0, 0,  0, 0, 0, 1]}])"),
       {"objects[0] transform is singular"}},
      {"zero scale", scene_json(R"("objects": [{"type": "transform", "scale": [1, 0, 1]}])"), {"objects[0] transform is singular"}},
      {"projective matrix",
       scene_json(R"("objects": [{"type": "transform", "matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 1, 0]}])"),
       {"objects[0].matrix must be affine"}},
      {"matrix of 15 numbers",
       scene_json(R"("objects": [{"type": "transform", "matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0]}])"),
       {"objects[0].matrix must be an array of 16 numbers"}},
      {"both transform forms",
       scene_json(R"("objects": [{"type": "transform", "matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1], "translate": [1, 0, 0]}])"),
       {"objects[0] has both 'matrix' and"}},
      {"triangle with two vertices", scene_json(R"("objects": [{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0]]}])"),
       {"objects[0].vertices must be an array of 3 points"}},
      {"collinear triangle", scene_json(R"("objects": [{"type": "triangle", "vertices": [[0, 0, 0], [1, 1, 1], [2, 2, 2]]}])"),
       {"objects[0].vertices must not be collinear"}},
      {"triangle beyond 1e30",
       scene_json(R"("objects": [{"type": "triangle", "vertices": [[0, 0, 0], [2e30, 0, 0], [0, 0, 1]]}])"),
       {"objects[0].vertices[1] has a coordinate beyond +-1e+30 (shadow rays reach 2^100"}},
      {"zero plane normal", scene_json(R"("objects": [{"type": "plane", "normal": [0, 0, 0]}])"), {"objects[0].normal must not be zero"}},
      {"empty gbuffer path", scene_json(R"("gbuffer": "")"), {"gbuffer must not be empty"}},
      {"syntax error", "{\n  \"camera\": {\"eye\": [0, 0, 5]},\n  \"ambient\": [0, 0,, 0]\n}", {"invalid JSON", "line 3, column"}},
      {"not an object", "[1, 2]", {"the top level must be an object"}},
      {"empty text", "", {"invalid JSON"}},
  };
  for (const ErrorCase& error_case : cases) {
    SCOPED_TRACE(error_case.what);
    const std::string message = error_of(error_case.json);
    EXPECT_EQ(message.rfind(kSource.string() + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& expected : error_case.expected)
      EXPECT_NE(message.find(expected), std::string::npos) << "message: " << message << "\nexpected: " << expected;
  }
}

// `depth` transforms, each the only child of the one before, around a sphere.
std::string nested_transforms(int depth) {
  std::string objects;
  for (int i = 0; i < depth; ++i) objects += R"({"type": "transform", "children": [)";
  objects += R"({"type": "sphere", "radius": 1})";
  for (int i = 0; i < depth; ++i) objects += "]}";
  return scene_json(R"("objects": [)" + objects + "]");
}

// 10,000 levels overflowed the stack of the recursive object reader (SIGSEGV) and 6,000 took
// 854 MB of path strings; now the parser refuses them with one line.
TEST(Scene, DeepNestingIsAOneLineErrorNotACrash) {
  for (int depth : {200, 10000, 100000}) {
    const std::string message = error_of(nested_transforms(depth));
    EXPECT_NE(message.find("some/dir/scene.json: invalid JSON: nested deeper than 256 levels"), std::string::npos)
        << "depth " << depth << ": " << message;
  }
  // Plain arrays count as well: nothing past the limit reaches the readers.
  EXPECT_NE(error_of(scene_json(R"("lights": )" + std::string(300, '[') + std::string(300, ']'))).find("nested deeper"),
            std::string::npos);
}

TEST(Scene, NestingWithinTheLimitParses) {
  const Scene scene = parse_scene(nested_transforms(120), kSource);
  const Object* object = &scene.objects.at(0);
  int depth = 0;
  for (; object->kind == Object::Kind::transform; ++depth) object = &object->children.at(0);
  EXPECT_EQ(depth, 120);
  EXPECT_EQ(object->kind, Object::Kind::sphere);
}

TEST(Scene, MissingFileCannotBeOpened) {
  const std::filesystem::path missing = std::filesystem::temp_directory_path() / "phongcl-no-such-dir" / "scene.json";
  try {
    load_scene(missing);
    FAIL() << "loaded a missing file";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), missing.string() + ": cannot open");
  }
}

// Row-major text must land in GLM's column-major storage so that the last column translates.
TEST(Scene, RowMajorMatrixTranslatesPoints) {
  const Scene scene = parse_scene(scene_json(R"("objects": [
      {"type": "transform", "matrix": [1, 0, 0, 5,  0, 1, 0, 6,  0, 0, 1, 7,  0, 0, 0, 1]},
      {"type": "transform", "matrix": [0, -1, 0, 0,  1, 0, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}])"),
                                  kSource);
  EXPECT_EQ(scene.objects.at(0).matrix * glm::dvec4(1, 1, 1, 1), glm::dvec4(6, 7, 8, 1));
  // A quarter turn about +z takes +x to +y (counter-clockwise seen from +z).
  EXPECT_EQ(scene.objects.at(1).matrix * glm::dvec4(1, 0, 0, 1), glm::dvec4(0, 1, 0, 1));
}

// T * R * S, rotations about X first: each expected point is worked out by hand.
TEST(Scene, TransformPartsComposeScaleThenRotateXYZThenTranslate) {
  const Scene scene = parse_scene(scene_json(R"("objects": [
      {"type": "transform", "translate": [1, 0, 0], "scale": [2, 1, 1]},
      {"type": "transform", "rotate_deg": [90, 90, 0]},
      {"type": "transform", "translate": [0, 0, 10], "rotate_deg": [0, 0, 90], "scale": [3, 3, 3]}])"),
                                  kSource);
  const auto moved = [&](std::size_t object, glm::dvec3 point) {
    return glm::dvec3(scene.objects.at(object).matrix * glm::dvec4(point, 1.0));
  };
  const auto expect_near = [](glm::dvec3 actual, glm::dvec3 expected) {
    EXPECT_LT(glm::length(actual - expected), 1e-12) << "got (" << actual.x << ", " << actual.y << ", " << actual.z << ")";
  };
  expect_near(moved(0, {1, 0, 0}), {3, 0, 0});    // scaled to 2, then moved by 1 (not (1+1)*2)
  expect_near(moved(1, {0, 1, 0}), {1, 0, 0});    // X: +y -> +z, then Y: +z -> +x
  expect_near(moved(2, {1, 0, 0}), {0, 3, 10});   // scaled, turned to +y, lifted along z
}

// The camera is optional: shade may take it from the G-buffer's header (gbuffer/file_camera.h).
TEST(Scene, CameraIsOptional) {
  const Scene without = parse_scene(R"({"materials": []})", "s.json");
  EXPECT_FALSE(without.has_camera);
  const Scene with = parse_scene(R"({"camera": {"eye": [1, 2, 3]}})", "s.json");
  EXPECT_TRUE(with.has_camera);
  EXPECT_EQ(with.camera.eye, glm::dvec3(1, 2, 3));
}

TEST(CameraSpace, TheCameraGoesToTheOriginLookingDownMinusZ) {
  const Scene scene = load_scene(kDefaultScene);
  const glm::dmat4 view = world_to_camera(scene.camera);
  const glm::dvec3 eye(view * glm::dvec4(scene.camera.eye, 1.0));
  const glm::dvec3 target(view * glm::dvec4(scene.camera.look_at, 1.0));
  EXPECT_NEAR(glm::length(eye), 0.0, 1e-12);
  EXPECT_NEAR(target.x, 0.0, 1e-12);
  EXPECT_NEAR(target.y, 0.0, 1e-12);
  EXPECT_NEAR(target.z, -glm::length(scene.camera.look_at - scene.camera.eye), 1e-12);
  const Scene moved = to_camera_space(scene);
  EXPECT_EQ(moved.camera.eye, glm::dvec3(0.0));
  EXPECT_EQ(moved.camera.look_at, glm::dvec3(0.0, 0.0, -1.0));
  ASSERT_EQ(moved.lights.size(), scene.lights.size());
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {  // rigid: distances to the eye are kept
    if (scene.lights[i].type == LightType::point)
      EXPECT_NEAR(glm::length(moved.lights[i].position), glm::length(scene.lights[i].position - scene.camera.eye), 1e-12);
    else
      EXPECT_NEAR(glm::length(moved.lights[i].direction), glm::length(scene.lights[i].direction), 1e-12);
  }
  Scene with_area = scene;
  AreaLight area;
  area.position = scene.camera.eye + glm::dvec3(0.0, 2.0, 0.0);
  with_area.area_lights = {area};
  const Scene moved_area = to_camera_space(with_area);
  ASSERT_EQ(moved_area.area_lights.size(), 1u);
  EXPECT_NEAR(glm::length(moved_area.area_lights[0].position), 2.0, 1e-12);
  EXPECT_NEAR(glm::dot(moved_area.area_lights[0].direction, moved_area.area_lights[0].up),
              glm::dot(area.direction, area.up), 1e-12);
}

}  // namespace
}  // namespace phongcl
