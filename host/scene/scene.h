#pragma once
// The scene file (JSON) as plain, validated structs; docs/formats.md "Scene JSON" is its reference.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace phongcl {

struct Camera {
  glm::dvec3 eye{0.0, 0.0, 5.0};
  glm::dvec3 look_at{0.0, 0.0, 0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_y_deg = 45.0;
  int width = 640;
  int height = 480;
};

enum class LightType { point, directional, spot };

// How a point or spot light dims with distance d: 1, 1/d, 1/d^2, 1/d^3 (the enum value is the power).
enum class Falloff { none = 0, linear = 1, quadratic = 2, cubic = 3 };

// The most shadow rays a light traces per pixel: 1024 rays put the penumbra's sampling error near
// float's rounding of the fraction (docs/shadows.md "Soft shadows"); more only costs.
inline constexpr int kMaxShadowRays = 1024;
// An environment's visibility rays: up to 4096, the converged estimate its error is measured against
// (docs/environment.md "Visibility").
inline constexpr int kMaxEnvironmentRays = 4096;

struct Light {
  LightType type = LightType::point;
  glm::dvec3 position{0.0};   // point and spot lights
  glm::dvec3 direction{0.0};  // directional: the way the light travels (l = -normalize); spot: where it points
  glm::dvec3 color{1.0};
  Falloff falloff = Falloff::none;                     // point and spot
  double range = 0.0;                                  // > 0: windowed to 0 at this distance; 0: no range
  double cone_angle_deg = 0.0, penumbra_angle_deg = 0.0;  // spot: full angle of the lit cone, soft edge
  double cosine_power = 0.0;                           // spot: F gains max(0, dot(-l, axis))^p; 0: none
  std::optional<std::vector<int>> materials{};         // light linking: lights only these; absent: every material
  bool shadows = false;                                // casts shadows (when the shade's shadow mode is not off)
  double radius = 0.0;     // point and spot: a sphere's radius, whose shadow is soft (docs/shadows.md); 0: a point
  double angle_deg = 0.0;  // directional: the sun's angular diameter, in [0, 180), whose shadow is soft; 0: none
  int shadow_rays = 0;     // with a size: rays for its soft shadow (1 to kMaxShadowRays); 0: the shade's
  std::string group{};                                 // light group: its light also goes to that layer; empty: none

  bool has_range() const { return range > 0.0; }
  bool has_size() const { return radius > 0.0 || angle_deg > 0.0; }
  bool reaches(int material) const;  // light linking
  bool operator==(const Light&) const = default;
};

// The specular lobe (docs/shading.md "Specular models"): Phong's (v.r)^q, the default;
// Blinn's (n.h)^q; each as is (the classic highlight, no cosine) or normalised, a BRDF times pi
// that takes the cosine n.l and reflects at most what it receives: (q+2)/2 (v.r)^q (Lafortune and
// Willems 1994), (q+8)/8 (n.h)^q (Akenine-Moller et al., Real-Time Rendering). The enum value is
// the kernel's model number (kernels/specular.h).
// kSpecularModels are the Phong family; `principled` is none of them: Cycles' Principled BSDF, version 1 or 2
// (docs/shading.md "Principled", "Principled v2"), from the material's base_color ... version fields instead of kd,
// ks and shininess. Its version 2 is the kernel's model 5 (kernel_specular_model).
enum class SpecularModel { phong = 0, phong_normalized = 1, blinn_phong = 2, blinn_phong_normalized = 3, principled = 4 };
// The kernel's model number (kernels/specular.h, principled.h): the enum's, 5 for Principled v2.
inline int kernel_specular_model(SpecularModel model, int version) {
  return model == SpecularModel::principled && version == 2 ? 5 : static_cast<int>(model);
}
inline constexpr SpecularModel kSpecularModels[] = {SpecularModel::phong, SpecularModel::phong_normalized,
                                                    SpecularModel::blinn_phong, SpecularModel::blinn_phong_normalized};

// A one-sided Lambertian emitter (docs/shading.md "Area lights"): a rectangle or a disk around
// `position`, lighting the side its unit `direction` points to. Its colour is a radiance with the
// diffuse 1/pi folded in, like a point light's Li: a surface facing it sees kd * color * (the
// emitter's solid angle weighted by n.l). Kept apart from `lights`: nothing that loops over point,
// spot and directional lights has to know about it.
enum class AreaShape { rect, disk };

struct AreaLight {
  AreaShape shape = AreaShape::rect;
  glm::dvec3 position{0.0};
  glm::dvec3 direction{0.0, 0.0, -1.0};  // the emitting side's normal; any length but zero
  glm::dvec3 up{0.0, 1.0, 0.0};          // rect: the side of size[1] runs along up, projected off direction
  glm::dvec2 size{1.0};                  // rect: width, height; disk: the diameter in x (the reader sets y to it too)
  glm::dvec3 color{1.0};
  double range = 0.0;  // > 0: windowed to 0 at this distance from the centre (as a point light's); 0: no range
  bool shadows = false;  // casts a shadow (when the shadow mode is not off): soft, or hard with one ray
  int shadow_rays = 0;   // rays over the emitter for its shadow in geometry mode, 1 to 1024 (1: one ray to the
                         // centre, a hard shadow); 0: the shade's ShadowSettings::rays
  std::string group{};   // light group, as a Light's; empty: none

  bool has_range() const { return range > 0.0; }
  bool operator==(const AreaLight&) const = default;
};

const char* to_string(AreaShape shape);  // "rect", "disk"
// std::invalid_argument naming the shapes for any other name.
AreaShape parse_area_shape(const std::string& name);

// The world's light (docs/environment.md): a uniform colour or an equirectangular float EXR in
// Blender's orientation, arriving from every direction. Its radiance is the world's L(w); a
// Lambertian surface of albedo kd sees kd * (1/pi) * integral L(w) max(0, n.w) dw, as Cycles' diffuse
// direct light does. Kept apart from `lights`, as AreaLight is; a scene holds at most one.
struct EnvironmentLight {
  glm::dvec3 color{1.0};          // the uniform world's radiance (without "file")
  std::filesystem::path file{};   // equirect EXR, resolved relative to the scene file; empty: uniform colour
  double rotation_deg = 0.0;      // about +Z, as Blender's Mapping node's Z rotation of the lookup
  double strength = 1.0;          // multiplies the radiance
  int rays = 0;                   // visibility rays per pixel, 1 to kMaxEnvironmentRays; 0: the shade's --environment-rays
  bool shadows = true;            // blocked by the scene's geometry (when the shadow mode is not off)
  std::string group{};            // light group, as a Light's; empty: none
  // The shading frame's directions into the world's: identity, or the view's inverse rotation once a
  // scene is moved to camera space (scene/camera_space.h). Not in the file.
  glm::dmat3 to_world{1.0};

  bool operator==(const EnvironmentLight&) const = default;
};

struct Material {
  std::string name;
  glm::dvec3 ka{0.0}, kd{0.0}, ks{0.0};
  double shininess = 1.0;  // >= 0, validated
  SpecularModel specular_model = SpecularModel::phong;
  // With specular_model principled, the node's inputs (Blender's defaults): kd, ks and shininess unused.
  glm::dvec3 base_color{0.8};
  double metallic = 0.0;       // [0, 1]
  double roughness = 0.5;      // [0, 1]; GGX's alpha is its square
  double specular = 0.5;       // [0, 12]: F0 = 0.08 specular for a dielectric
  double specular_tint = 0.0;  // [0, 1]: towards the base colour's hue
  int version = 1;             // the node's version: 1 (Blender 2.8 to 3.6) or 2 (Blender 4.0 on)
  // Version 2's own inputs (specular and specular_tint above are version 1's):
  double ior = 1.5;                    // [1, 1000]: the dielectric's index
  double specular_ior_level = 0.5;     // >= 0: scales F0(ior) by twice itself
  glm::dvec3 specular_tint_color{1.0}; // >= 0: tints the dielectric's F0 and the metal's F82 edge
  double diffuse_roughness = 0.0;      // [0, 1]: Oren-Nayar's sigma; Lambert's diffuse below 1e-5

  bool operator==(const Material&) const = default;
};

// Geometry for the G-buffer generator and for shadows. A tagged struct rather than a variant: transforms nest.
struct Object {
  enum class Kind { sphere, plane, triangle, mesh, transform };
  Kind kind = Kind::sphere;
  int material = 0;                          // sphere, plane, triangle
  glm::dvec3 center{0.0};                    // sphere
  double radius = 1.0;                       // sphere
  glm::dvec3 normal{0.0, 1.0, 0.0};          // plane: points x with dot(normalize(normal), x) == offset
  double offset = 0.0;                       // plane
  std::array<glm::dvec3, 3> vertices{};      // triangle, counter-clockwise seen from the front
  std::filesystem::path file{};              // mesh: its triangles' file (PLY, OBJ, glTF), resolved relative to the scene
  glm::dmat4 matrix{1.0};                    // transform: object-to-parent
  std::vector<Object> children{};            // transform

  bool operator==(const Object&) const = default;
};

// The lights as the renderer had them when it rendered the passes a composite starts from (a scene
// file's "rendered", written by scripts/blender/export_scene.py beside the lights the artist edits):
// what decides which light groups changed (composite/group_edits.h).
struct RenderedLights {
  std::vector<Light> lights;
  std::vector<AreaLight> area_lights;
  std::optional<EnvironmentLight> environment{};  // kept as read; composites do not relight the world
};

struct Scene {
  Camera camera;
  bool has_camera = true;  // false when the file has no "camera" (shade may take it from the G-buffer)
  glm::dvec3 background{0.0};
  glm::dvec3 ambient{0.0};
  std::vector<Light> lights;
  std::vector<AreaLight> area_lights;  // the file's lights of type "area", in file order
  std::optional<EnvironmentLight> environment{};  // the file's light of type "environment", if any
  std::vector<Material> materials;
  std::vector<Object> objects;
  std::optional<RenderedLights> rendered;  // "rendered": {"lights": [...]}; absent: none stated
  // "color_space": the OCIO colour space the colours above are in (lights, materials, ambient,
  // background); empty: the working space. Front ends convert them (color/color_conversion.h) and
  // empty it; the Relighter refuses a scene whose colours are not converted yet.
  std::string color_space;
  std::filesystem::path gbuffer;  // optional "gbuffer" entry, resolved relative to the scene file; empty if absent
  std::filesystem::path source;   // the scene file, for messages
};

// Reads and validates a scene file. Throws InputError naming the file and the problem (syntax,
// unknown key, wrong type, unknown light type, negative shininess, material index out of range...).
Scene load_scene(const std::filesystem::path& file);
// The same from text; `source` is used in messages and to resolve the relative "gbuffer" path.
Scene parse_scene(std::string_view json_text, const std::filesystem::path& source);

const char* to_string(Falloff falloff);  // "none", "linear", ...
const char* to_string(SpecularModel model);  // "phong", "blinn-phong-normalized", ...
// The model a name stands for; std::invalid_argument naming the allowed names otherwise.
SpecularModel parse_specular_model(const std::string& name);

// The scene's light groups, each name once, in the order of the lights that first name them: the
// point, spot and directional lights first, then the area lights, then the environment.
std::vector<std::string> light_groups(const std::vector<Light>& lights, const std::vector<AreaLight>& area_lights = {},
                                      const std::optional<EnvironmentLight>& environment = std::nullopt);

}  // namespace phongcl
