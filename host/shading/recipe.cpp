#include "shading/recipe.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "shading/device_layout.h"

namespace phongcl {

namespace {

bool is_zero(const glm::dvec3& c) { return c.x == 0.0 && c.y == 0.0 && c.z == 0.0; }

bool all_zero(const Planes3& planes) {
  return std::all_of(planes.begin(), planes.end(),
                     [](const Plane& plane) { return std::all_of(plane.begin(), plane.end(), [](float x) { return x == 0.0f; }); });
}

void decide_terms(Recipe& recipe, const Scene& scene, const GBuffer& gbuffer) {
  const auto& materials = scene.materials;
  const bool any_lights = !scene.lights.empty();
  const bool table_ks_zero = std::all_of(materials.begin(), materials.end(), [](const Material& m) { return is_zero(m.ks); });
  const bool ks_zero = gbuffer.has_per_pixel_ks() ? all_zero(gbuffer.ks) : table_ks_zero;
  recipe.specular = any_lights && !ks_zero;
  recipe.reasons.push_back(recipe.specular ? "specular: compiled in (some material has ks > 0)"
                           : any_lights    ? "specular: compiled out (every ks is 0): no pow"
                                           : "specular: compiled out (no lights)");

  const bool table_ka_zero = std::all_of(materials.begin(), materials.end(), [](const Material& m) { return is_zero(m.ka); });
  const bool ka_zero = gbuffer.has_per_pixel_ka() ? all_zero(gbuffer.ka) : table_ka_zero;
  recipe.ambient = !is_zero(scene.ambient) && !ka_zero;
  recipe.reasons.push_back(recipe.ambient            ? "ambient: compiled in"
                           : is_zero(scene.ambient) ? "ambient: compiled out (ambient light is 0)"
                                                    : "ambient: compiled out (every ka is 0)");
}

void count_lights(Recipe& recipe, const Scene& scene) {
  for (const Light& light : scene.lights) {
    (light.type == LightType::directional ? recipe.directional_lights : recipe.point_lights)++;
    if (light.type == LightType::spot) ++recipe.spot_lights;
  }
}

int link_words_for(const Scene& scene) { return std::max<int>(1, (static_cast<int>(scene.materials.size()) + 31) / 32); }

// Falloff, range windows, spot cones and linking: compiled in for the scenes that use them.
void decide_light_shapes(Recipe& recipe, const Scene& scene) {
  std::set<int> powers;
  bool any_range = false, any_link = false;
  for (const Light& light : scene.lights) {
    any_link |= light.materials.has_value();
    if (light.type == LightType::directional) continue;
    powers.insert(static_cast<int>(light.falloff));
    any_range |= light.has_range();
  }
  recipe.falloff_mixed = powers.size() > 1;
  recipe.falloff_power = powers.size() == 1 ? *powers.begin() : 0;
  recipe.range_window = any_range;
  recipe.spot_code = recipe.spot_lights > 0;
  recipe.link_words = any_link ? link_words_for(scene) : 0;
  recipe.reasons.push_back(recipe.falloff_mixed       ? "falloff: mixed powers, each light's read at run time"
                           : recipe.falloff_power > 0 ? "falloff: 1/d^" + std::to_string(recipe.falloff_power) +
                                                            " for every point and spot light, compiled in"
                                                      : "falloff: compiled out (no light has one)");
  recipe.reasons.push_back(recipe.range_window ? "range window: compiled in (some light has a range)"
                                               : "range window: compiled out (no light has a range)");
  recipe.reasons.push_back(recipe.spot_code ? "spot cones: compiled in (" + std::to_string(recipe.spot_lights) + " spots)"
                                            : "spot cones: compiled out (no spots)");
  recipe.reasons.push_back(recipe.link_words > 0 ? "light linking: compiled in (" + std::to_string(recipe.link_words) +
                                                       " mask word" + (recipe.link_words > 1 ? "s" : "") + " per light)"
                                                 : "light linking: compiled out (every light lights every material)");
}

// Needs recipe.point_lights. Culling pays where many lights have small ranges: a tile then keeps a
// few of them. Without ranges every light reaches every tile, and culling would only add its cost.
void decide_culling(Recipe& recipe, const Scene& scene, const ShadeOptions& options) {
  if (options.tile_size < 1 || options.tile_size > 1024)
    throw std::invalid_argument("tile size must be 1 to 1024 pixels, not " + std::to_string(options.tile_size));
  recipe.tile_size = options.tile_size;
  const auto ranged = std::count_if(scene.lights.begin(), scene.lights.end(), [](const Light& light) {
    return light.type != LightType::directional && light.has_range();
  });
  const bool pays = ranged >= kAutoCullingLights;
  recipe.tiled = recipe.point_lights > 0 && (options.culling == Culling::tiled || (options.culling == Culling::automatic && pays));
  std::string line = "culling: ";
  if (recipe.point_lights == 0) line += "none (no point or spot lights)";
  else if (options.culling == Culling::none) line += "none (as asked)";
  else if (options.culling == Culling::tiled) line += "tiled, " + std::to_string(recipe.tile_size) + "x" + std::to_string(recipe.tile_size) + " (as asked)";
  else if (recipe.tiled) line += "tiled, " + std::to_string(recipe.tile_size) + "x" + std::to_string(recipe.tile_size) + " (" +
                                 std::to_string(ranged) + " point/spot lights with a range, at least " +
                                 std::to_string(kAutoCullingLights) + ")";
  else line += "none (" + std::to_string(ranged) + " point/spot lights with a range, fewer than " +
               std::to_string(kAutoCullingLights) + ")";
  recipe.reasons.push_back(line);
}

void decide_lights(Recipe& recipe) {
  recipe.point_code = recipe.point_lights > 0;
  recipe.directional_code = recipe.directional_lights > 0;
  // Tiled: each tile's count is its list's.
  recipe.point_count_in_code = recipe.point_code && !recipe.tiled && recipe.point_lights <= kUnrollLightLimit;
  recipe.directional_count_in_code = recipe.directional_code && recipe.directional_lights <= kUnrollLightLimit;
  auto describe = [](const char* type, int count, bool in_code) {
    if (count == 0) return std::string(type) + " lights: compiled out (none in the scene)";
    return std::string(type) + " lights: " + std::to_string(count) +
           (in_code ? ", count compiled in (loop unrolls)"
                    : ", count at run time (more than " + std::to_string(kUnrollLightLimit) + ")");
  };
  recipe.reasons.push_back(recipe.tiled ? "point and spot lights: " + std::to_string(recipe.point_lights) +
                                              ", each tile's list counted at run time"
                                        : describe("point and spot", recipe.point_lights, recipe.point_count_in_code));
  recipe.reasons.push_back(describe("directional", recipe.directional_lights, recipe.directional_count_in_code));
}

// Needs recipe.lanes.
void decide_materials(Recipe& recipe, const Scene& scene, const GBuffer& gbuffer) {
  recipe.per_pixel_ka = gbuffer.has_per_pixel_ka();
  recipe.per_pixel_kd = gbuffer.has_per_pixel_kd();
  recipe.per_pixel_ks = gbuffer.has_per_pixel_ks();
  recipe.per_pixel_shininess = gbuffer.has_per_pixel_shininess();
  const bool table_needed = !(recipe.per_pixel_ka && recipe.per_pixel_kd && recipe.per_pixel_ks && recipe.per_pixel_shininess);
  recipe.single_material = recipe.specialised && scene.materials.size() <= 1;
  recipe.material_count = static_cast<int>(scene.materials.size());
  recipe.material_selects = recipe.specialised && table_needed && !recipe.single_material && recipe.lanes > 1 &&
                            recipe.material_count <= recipe.lanes;
  std::string line = "materials: ";
  if (!table_needed) line += "all per-pixel channels (Ka, Kd, Ks, shininess)";
  else if (recipe.single_material) line += "single material, no per-pixel fetch";
  else if (recipe.material_selects) line += std::to_string(recipe.material_count) + " in a table, count compiled in (per-lane selects, no gather)";
  else line += std::to_string(scene.materials.size()) + " in a table, indexed per pixel";
  if (table_needed && (recipe.per_pixel_ka || recipe.per_pixel_kd || recipe.per_pixel_ks || recipe.per_pixel_shininess)) {
    line += "; per-pixel overrides:";
    if (recipe.per_pixel_ka) line += " Ka";
    if (recipe.per_pixel_kd) line += " Kd";
    if (recipe.per_pixel_ks) line += " Ks";
    if (recipe.per_pixel_shininess) line += " shininess";
  }
  recipe.reasons.push_back(line);
}

void decide_memory(Recipe& recipe, const Scene& scene, const DeviceInfo& device) {
  const bool shapes = recipe.falloff_power > 0 || recipe.falloff_mixed || recipe.range_window || recipe.spot_code;
  const unsigned long long bytes = recipe.point_lights * sizeof(PointLight) +
                                   recipe.directional_lights * sizeof(DirectionalLight) +
                                   std::max<std::size_t>(scene.materials.size(), 1) * sizeof(MaterialRecord) +
                                   (shapes ? recipe.point_lights * sizeof(LightShape) : 0) +
                                   (recipe.point_lights + recipe.directional_lights) * recipe.link_words * sizeof(LinkWord);
  // Five tables: materials, point and directional lights, light shapes, linking masks.
  recipe.uniforms_in_constant = recipe.specialised && device.max_constant_args >= 5 && bytes <= device.max_constant_buffer;
  recipe.reasons.push_back(recipe.uniforms_in_constant
                               ? "lights and materials: __constant memory (" + std::to_string(bytes) + " bytes fit)"
                               : "lights and materials: __global memory");
}

// PoCL does not vectorise this kernel across work-items by itself, so on a CPU each work-item
// shades one SIMD register's worth of pixels (16 floats with AVX-512: 1.6x faster than 8 here);
// GPUs want one pixel per work-item. OpenCL vectors come in powers of two up to 16.
// A double is two floats wide: one register holds half as many (and double16 with every light
// shape overflowed PoCL's work-item stacks: it keeps each work-item's spilled vectors apart).
int lanes_for(const DeviceInfo& device, Precision precision) {
  if (!device.is_cpu) return 1;
  const unsigned width = precision == Precision::double_precision ? device.preferred_float_width / 2 : device.preferred_float_width;
  int lanes = 1;
  while (lanes < 16 && static_cast<unsigned>(lanes * 2) <= width) lanes *= 2;
  return lanes;
}

}  // namespace

Culling parse_culling(const std::string& name) {
  if (name == "auto") return Culling::automatic;
  if (name == "tiled") return Culling::tiled;
  if (name == "none") return Culling::none;
  throw std::invalid_argument("unknown culling '" + name + "' (expected auto, tiled or none)");
}

int Recipe::plane_count() const {
  return PLANE_GEOMETRY_COUNT + 3 * (per_pixel_ka + per_pixel_kd + per_pixel_ks) + per_pixel_shininess;
}

std::string Recipe::build_options() const {
  std::string options = "-cl-std=CL1.2";
  auto define = [&options](const std::string& name) { options += " -D" + name; };
  define("PHONGCL_LANES=" + std::to_string(lanes));
  if (point_code) define("POINT_LIGHTS");
  if (directional_code) define("DIRECTIONAL_LIGHTS");
  if (point_count_in_code) define("POINT_COUNT=" + std::to_string(point_lights));
  if (directional_count_in_code) define("DIRECTIONAL_COUNT=" + std::to_string(directional_lights));
  if (specular) define("SPECULAR");
  if (ambient) define("AMBIENT");
  if (single_material) define("SINGLE_MATERIAL");
  if (material_selects) define("MATERIAL_COUNT=" + std::to_string(material_count));
  int plane = PLANE_GEOMETRY_COUNT;
  auto place = [&](bool present, const char* name, int planes) {
    if (!present) return;
    define(std::string(name) + "=" + std::to_string(plane));
    plane += planes;
  };
  place(per_pixel_ka, "PLANE_KA", 3);
  place(per_pixel_kd, "PLANE_KD", 3);
  place(per_pixel_ks, "PLANE_KS", 3);
  place(per_pixel_shininess, "PLANE_Q", 1);
  if (falloff_mixed) define("FALLOFF_MIXED");
  else if (falloff_power > 0) define("FALLOFF=" + std::to_string(falloff_power));
  if (range_window) define("RANGE_WINDOW");
  if (spot_code) define("SPOT_LIGHTS");
  if (link_words > 0) define("LIGHT_LINKING=" + std::to_string(link_words));
  if (tiled) define("TILED_CULLING");
  if (write_terms) define("WRITE_TERMS");
  define(std::string("UNIFORM_SPACE=") + (uniforms_in_constant ? "__constant" : "__global"));
  switch (precision) {
    case Precision::double_precision: define("PHONGCL_DOUBLE"); break;
    case Precision::precise: break;
    case Precision::fast: define("PHONGCL_FAST"); options += " -cl-fast-relaxed-math"; break;
    case Precision::half_storage: define("HALF_STORAGE"); break;
  }
  return options;
}

std::string Recipe::summary() const {
  std::string text = to_string(precision) + (specialised ? ", specialised: " : ", general kernel: ");
  auto lights = [](int count, const char* type, bool unrolled) {
    return std::to_string(count) + " " + type + (unrolled ? " (unrolled)" : "");
  };
  text += lights(point_lights - spot_lights, "point", point_count_in_code) + " + " +
          (spot_lights > 0 ? lights(spot_lights, "spot", point_count_in_code) + " + " : std::string()) +
          lights(directional_lights, "directional", directional_count_in_code) + " lights";
  if (falloff_mixed) text += ", mixed falloff";
  else if (falloff_power > 0) text += ", 1/d^" + std::to_string(falloff_power) + " falloff";
  if (range_window) text += ", ranges";
  if (link_words > 0) text += ", light linking";
  if (tiled) text += ", tiled culling " + std::to_string(tile_size) + "x" + std::to_string(tile_size);
  text += specular ? ", specular" : ", no specular";
  text += ambient ? ", ambient" : ", no ambient";
  text += single_material ? ", single material" : material_selects ? ", material table (selects)" : ", material table";
  if (plane_count() > PLANE_GEOMETRY_COUNT) text += ", per-pixel material channels";
  return text;
}

Recipe make_recipe(const Scene& scene, const GBuffer& gbuffer, const DeviceInfo& device, const ShadeOptions& options) {
  if (options.precision == Precision::double_precision && !device.has_fp64) {
    throw std::runtime_error("--precision double: device " + device.name + " has no fp64 support (cl_khr_fp64)");
  }
  Recipe recipe;
  recipe.precision = options.precision;
  recipe.specialised = options.specialise;
  recipe.write_terms = options.write_terms;
  recipe.reasons.push_back("precision: " + to_string(options.precision));
  count_lights(recipe, scene);
  recipe.lanes = options.lanes > 0 ? options.lanes : lanes_for(device, options.precision);
  if (recipe.lanes > 16 || (recipe.lanes & (recipe.lanes - 1)) != 0) {
    throw std::invalid_argument("lanes must be 1, 2, 4, 8 or 16 (OpenCL vector widths), not " +
                                std::to_string(recipe.lanes));
  }
  decide_materials(recipe, scene, gbuffer);
  decide_culling(recipe, scene, options);
  if (recipe.specialised) {
    decide_lights(recipe);
    decide_terms(recipe, scene, gbuffer);
    decide_light_shapes(recipe, scene);
  } else {
    // The general kernel: every light type and term, counts at run time; the per-pixel planes
    // present are still compile-time, since they are the data layout, not the shading.
    recipe.point_code = recipe.directional_code = true;
    recipe.point_count_in_code = recipe.directional_count_in_code = false;
    recipe.specular = recipe.ambient = true;
    recipe.falloff_mixed = recipe.range_window = recipe.spot_code = true;
    recipe.link_words = link_words_for(scene);
    recipe.reasons.push_back("general kernel (--no-specialise): every light type and term compiled in, " +
                             std::to_string(recipe.point_lights) + " point and " +
                             std::to_string(recipe.directional_lights) +
                             " directional lights counted at run time; falloff, ranges, spot cones and linking too");
  }
  decide_memory(recipe, scene, device);
  recipe.reasons.push_back("lanes: " + std::to_string(recipe.lanes) + " pixel" + (recipe.lanes > 1 ? "s" : "") +
                           " per work-item (" +
                           (options.lanes > 0 ? "as asked"
                            : device.is_cpu   ? (options.precision == Precision::double_precision ? "CPU: explicit SIMD, half the device's preferred float vector width (doubles)" : "CPU: explicit SIMD, the device's preferred float vector width")
                                              : "GPU: one pixel each") +
                           ")");
  return recipe;
}

}  // namespace phongcl
