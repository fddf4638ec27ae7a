#include "shading/recipe.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "environment/irradiance_map.h"
#include "shading/pack_environment_specular.h"
#include "shading/pack_principled_v2.h"
#include "shading/device_layout.h"

namespace phongcl {

namespace {

std::string plural(int count, const std::string& word) { return std::to_string(count) + " " + word + (count == 1 ? "" : "s"); }

// Adds a row to the recipe's table and returns its value, so that a decision reads as one statement.
bool add_flag(Recipe& recipe, const std::string& name, bool on, const std::string& why, const std::string& summary = "") {
  recipe.flags.push_back({name, on ? "1" : "0", why, summary});
  return on;
}
int add_count(Recipe& recipe, const std::string& name, int value, const std::string& why, const std::string& summary = "") {
  recipe.flags.push_back({name, std::to_string(value), why, summary});
  return value;
}

bool is_zero(const glm::dvec3& c) { return c.x == 0.0 && c.y == 0.0 && c.z == 0.0; }

bool all_zero(const Planes3& planes) {
  return std::all_of(planes.begin(), planes.end(),
                     [](const Plane& plane) { return std::all_of(plane.begin(), plane.end(), [](float x) { return x == 0.0f; }); });
}

// PoCL does not vectorise this kernel across work-items by itself, so on a CPU each work-item
// shades one SIMD register's worth of pixels (16 floats with AVX-512: 1.6x faster than 8 here);
// GPUs want one pixel per work-item. OpenCL vectors come in powers of two up to 16.
// A double is two floats wide: one register holds half as many.
int lanes_for(const DeviceInfo& device, Precision precision) {
  if (!device.is_cpu) return 1;
  const unsigned width = precision == Precision::double_precision ? device.preferred_float_width / 2 : device.preferred_float_width;
  int lanes = 1;
  while (lanes < 16 && static_cast<unsigned>(lanes * 2) <= width) lanes *= 2;
  return lanes;
}

// Doubles on a CPU: at most 8 lanes. double16 overflows PoCL's work-group stack (its context keeps
// every work-item's spilled vectors apart); images do not depend on the lane count.
constexpr int kMaxCpuDoubleLanes = 8;

void decide_lanes(Recipe& recipe, const DeviceInfo& device, const ShadeOptions& options) {
  recipe.lanes = options.lanes > 0 ? options.lanes : lanes_for(device, options.precision);
  if (recipe.lanes > 16 || (recipe.lanes & (recipe.lanes - 1)) != 0) {
    throw std::invalid_argument("lanes must be 1, 2, 4, 8 or 16 (OpenCL vector widths), not " +
                                std::to_string(recipe.lanes));
  }
  const bool capped =
      device.is_cpu && options.precision == Precision::double_precision && recipe.lanes > kMaxCpuDoubleLanes;
  if (capped) recipe.lanes = kMaxCpuDoubleLanes;
  const std::string why = capped            ? std::to_string(options.lanes) + " asked; doubles on a CPU take at most " +
                                                  std::to_string(kMaxCpuDoubleLanes) + ": double16 overflows PoCL's work-group stack"
                          : options.lanes > 0 ? "as asked"
                          : !device.is_cpu  ? "GPU: one pixel each"
                          : options.precision == Precision::double_precision
                              ? "CPU: explicit SIMD, half the device's preferred float vector width (doubles)"
                              : "CPU: explicit SIMD, the device's preferred float vector width";
  add_count(recipe, "PHONGCL_LANES", recipe.lanes, "lanes: " + plural(recipe.lanes, "pixel") + " per work-item (" + why + ")");
}

void decide_precision(Recipe& recipe, Precision precision) {
  recipe.precision = precision;
  const std::string name = "precision: " + to_string(precision);
  add_flag(recipe, "PHONGCL_DOUBLE", precision == Precision::double_precision,
           name + (precision == Precision::double_precision ? ", fp64 arithmetic" : ", float arithmetic"));
  add_flag(recipe, "PHONGCL_FAST", precision == Precision::fast,
           name + (precision == Precision::fast ? ", built with -cl-fast-relaxed-math" : ", IEEE semantics"));
  add_flag(recipe, "HALF_STORAGE", precision == Precision::half_storage,
           name + (precision == Precision::half_storage ? ", G-buffer stored as half" : ", G-buffer stored as float"));
}

void count_lights(Recipe& recipe, const Scene& scene) {
  for (const Light& light : scene.lights) {
    (light.type == LightType::directional ? recipe.directional_lights : recipe.point_lights)++;
    if (light.type == LightType::spot) ++recipe.spot_lights;
  }
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
  const bool tiled =
      recipe.point_lights > 0 && (options.culling == Culling::tiled || (options.culling == Culling::automatic && pays));
  const std::string size = std::to_string(recipe.tile_size) + "x" + std::to_string(recipe.tile_size);
  std::string line = "culling: ";
  if (recipe.point_lights == 0) line += "none (no point or spot lights)";
  else if (options.culling == Culling::none) line += "none (as asked)";
  else if (options.culling == Culling::tiled) line += "tiled, " + size + " (as asked)";
  else if (tiled) line += "tiled, " + size + " (" + std::to_string(ranged) + " point/spot lights with a range, at least " +
                          std::to_string(kAutoCullingLights) + ")";
  else line += "none (" + std::to_string(ranged) + " point/spot lights with a range, fewer than " +
               std::to_string(kAutoCullingLights) + ")";
  recipe.tiled = add_flag(recipe, "TILED_CULLING", tiled, line, tiled ? "tiled culling " + size : "");
}

// Needs recipe.tiled. Up to kUnrollLightLimit lights of a type, the count is compiled in and the
// loop unrolls; a tile's list is counted at run time.
void decide_lights(Recipe& recipe) {
  const int points = recipe.point_lights, spots = recipe.spot_lights, directionals = recipe.directional_lights;
  if (!recipe.specialised) {
    const std::string why = "(general kernel, counted at run time)";
    add_flag(recipe, "POINT_LIGHTS", true, "point and spot lights: " + std::to_string(points) + " " + why,
             std::to_string(points - spots) + " point" + (spots > 0 ? " + " + std::to_string(spots) + " spot" : ""));
    add_count(recipe, "POINT_COUNT", 0, "point and spot light count: at run time (general kernel)");
    add_flag(recipe, "DIRECTIONAL_LIGHTS", true, "directional lights: " + std::to_string(directionals) + " " + why,
             std::to_string(directionals) + " directional");
    add_count(recipe, "DIRECTIONAL_COUNT", 0, "directional light count: at run time (general kernel)");
    return;
  }
  const bool point_in_code = points > 0 && !recipe.tiled && points <= kUnrollLightLimit;
  const bool directional_in_code = directionals > 0 && directionals <= kUnrollLightLimit;
  const std::string point_unrolled = point_in_code ? " (unrolled)" : "";
  add_flag(recipe, "POINT_LIGHTS", points > 0,
           points > 0 ? "point and spot lights: " + std::to_string(points) + " (" + std::to_string(spots) + " spots)"
                      : "point and spot lights: compiled out (none in the scene)",
           points == 0 ? ""
                       : std::to_string(points - spots) + " point" + point_unrolled +
                             (spots > 0 ? " + " + std::to_string(spots) + " spot" + point_unrolled : ""));
  add_count(recipe, "POINT_COUNT", point_in_code ? points : 0,
            points == 0      ? "point and spot light count: none"
            : point_in_code  ? "point and spot light count: compiled in (loop unrolls)"
            : recipe.tiled   ? "point and spot light count: each tile's list, at run time"
                             : "point and spot light count: at run time (more than " +
                                 std::to_string(kUnrollLightLimit) + ")");
  add_flag(recipe, "DIRECTIONAL_LIGHTS", directionals > 0,
           directionals > 0 ? "directional lights: " + std::to_string(directionals)
                            : "directional lights: compiled out (none in the scene)",
           directionals > 0 ? std::to_string(directionals) + " directional" + (directional_in_code ? " (unrolled)" : "") : "");
  add_count(recipe, "DIRECTIONAL_COUNT", directional_in_code ? directionals : 0,
            directionals == 0    ? "directional light count: none"
            : directional_in_code ? "directional light count: compiled in (loop unrolls)"
                                  : "directional light count: at run time (more than " +
                                        std::to_string(kUnrollLightLimit) + ")");
}

int link_words_for(const Scene& scene) { return std::max<int>(1, (static_cast<int>(scene.materials.size()) + 31) / 32); }

// A spot's cosine power is compiled in only where some spot has one, in the general kernel too:
// the kernel without it is the one from before cosine powers, bit for bit (with the power multiplied
// in, -cl-fast-relaxed-math reorders the cone's products even where p = 0).
void decide_spot_cosine_power(Recipe& recipe, const Scene& scene) {
  const auto powered = std::count_if(scene.lights.begin(), scene.lights.end(), [](const Light& light) {
    return light.type == LightType::spot && light.cosine_power != 0.0;
  });
  add_flag(recipe, "SPOT_COSINE_POWER", powered > 0,
           powered > 0 ? "spot cosine power: compiled in (" + plural(static_cast<int>(powered), "spot") + " with p > 0)"
                       : "spot cosine power: compiled out (no spot has one)",
           powered > 0 ? "spot cosine power" : "");
}

// Falloff, range windows, spot cones and linking: compiled in for the scenes that use them, and
// always in the general kernel.
void decide_light_shapes(Recipe& recipe, const Scene& scene) {
  decide_spot_cosine_power(recipe, scene);
  std::set<int> powers;
  bool any_range = false, any_link = false;
  for (const Light& light : scene.lights) {
    any_link |= light.materials.has_value();
    if (light.type == LightType::directional) continue;
    powers.insert(static_cast<int>(light.falloff));
    any_range |= light.has_range();
  }
  if (!recipe.specialised) {
    const std::string general = " (general kernel)";
    add_count(recipe, "FALLOFF", 0, "falloff: each light's power read at run time" + general);
    add_flag(recipe, "FALLOFF_MIXED", true, "falloff: compiled in" + general, "mixed falloff");
    add_flag(recipe, "RANGE_WINDOW", true, "range window: compiled in" + general, "ranges");
    add_flag(recipe, "SPOT_LIGHTS", true, "spot cones: compiled in" + general);
    recipe.link_words = add_count(recipe, "LIGHT_LINKING", link_words_for(scene),
                                  "light linking: compiled in" + general, "light linking");
    return;
  }
  const bool mixed = powers.size() > 1;
  const int power = powers.size() == 1 ? *powers.begin() : 0;
  add_count(recipe, "FALLOFF", power,
            power > 0 ? "falloff: 1/d^" + std::to_string(power) + " for every point and spot light, compiled in"
            : mixed   ? "falloff: powers differ between lights (FALLOFF_MIXED)"
                      : "falloff: compiled out (no light has one)",
            power > 0 ? "1/d^" + std::to_string(power) + " falloff" : "");
  add_flag(recipe, "FALLOFF_MIXED", mixed,
           mixed ? "falloff: mixed powers, each light's read at run time" : "falloff: not mixed",
           mixed ? "mixed falloff" : "");
  add_flag(recipe, "RANGE_WINDOW", any_range,
           any_range ? "range window: compiled in (some light has a range)" : "range window: compiled out (no light has a range)",
           any_range ? "ranges" : "");
  add_flag(recipe, "SPOT_LIGHTS", recipe.spot_lights > 0,
           recipe.spot_lights > 0 ? "spot cones: compiled in (" + plural(recipe.spot_lights, "spot") + ")"
                                  : "spot cones: compiled out (no spots)");
  const int words = any_link ? link_words_for(scene) : 0;
  recipe.link_words = add_count(recipe, "LIGHT_LINKING", words,
                                words > 0 ? "light linking: compiled in (" + plural(words, "mask word") + " per light)"
                                          : "light linking: compiled out (every light lights every material)",
                                words > 0 ? "light linking" : "");
}

// The lobes the materials choose, decided by the scene in the general kernel too: Phong's alone is
// the kernel without specular models, bit for bit. A G-buffer has no model channel: a pixel takes its material's
// model from the table, as the coefficients it does not carry. Where it carries every one the
// table is not consulted (its indices need not be in it): phong, as with no table.
void decide_specular_models(Recipe& recipe, const Scene& scene, const GBuffer& gbuffer, bool specular) {
  const bool table_consulted = !(gbuffer.has_per_pixel_ka() && gbuffer.has_per_pixel_kd() && gbuffer.has_per_pixel_ks() &&
                                 gbuffer.has_per_pixel_shininess());
  unsigned mask = 0;
  if (table_consulted)
    for (const Material& material : scene.materials)
      mask |= 1u << kernel_specular_model(material.specular_model, material.version);
  if (!specular || mask == 0) mask = 1u << static_cast<int>(SpecularModel::phong);
  std::string names;
  for (SpecularModel model : kSpecularModels)
    if (mask & (1u << static_cast<int>(model))) names += (names.empty() ? "" : ", ") + std::string(to_string(model));
  if (mask & (1u << static_cast<int>(SpecularModel::principled)))
    names += (names.empty() ? "" : ", ") + std::string("principled (Cycles' Principled BSDF v1: GGX, Fresnel, Burley)");
  if (mask & (1u << kernel_specular_model(SpecularModel::principled, 2)))
    names += (names.empty() ? "" : ", ") +
             std::string("principled v2 (Cycles' Principled BSDF v2: multiscatter GGX, F82 tint, layered Lambert)");
  const bool phong_only = mask == 1u << static_cast<int>(SpecularModel::phong);
  const bool mixed = (mask & (mask - 1)) != 0;
  add_count(recipe, "SPECULAR_MODELS", static_cast<int>(mask),
            !specular          ? "specular models: none compiled in (no specular)"
            : !table_consulted ? "specular model: phong (every coefficient is per pixel: the table is not consulted)"
            : mixed            ? "specular models: " + names + " (the materials differ: each lane's model read from the table)"
                               : "specular model: " + names + (phong_only ? " (every material's)" : ", compiled in (every material's)"),
            phong_only ? "" : (mixed ? "specular models " : "specular model ") + names);
  const bool oren_nayar = (mask & (1u << kernel_specular_model(SpecularModel::principled, 2))) &&
                          std::ranges::any_of(scene.materials, takes_oren_nayar);
  add_flag(recipe, "OREN_NAYAR", oren_nayar,
           oren_nayar ? "diffuse: Oren-Nayar compiled in (a Principled v2 material's diffuse roughness)"
                      : "diffuse: Oren-Nayar compiled out (no Principled v2 material with a diffuse roughness)",
           oren_nayar ? "Oren-Nayar diffuse" : "");
}

void decide_terms(Recipe& recipe, const Scene& scene, const GBuffer& gbuffer) {
  if (!recipe.specialised) {
    add_flag(recipe, "SPECULAR", true, "specular: compiled in (general kernel)", "specular");
    decide_specular_models(recipe, scene, gbuffer, true);
    add_flag(recipe, "AMBIENT", true, "ambient: compiled in (general kernel)", "ambient");
    return;
  }
  const auto& materials = scene.materials;
  const bool any_lights = !scene.lights.empty() || !scene.area_lights.empty() || scene.environment.has_value();
  // A Principled material always has a specular lobe: at grazing angles its Fresnel reaches 1.
  const bool table_ks_zero = std::all_of(materials.begin(), materials.end(), [](const Material& m) {
    return is_zero(m.ks) && m.specular_model != SpecularModel::principled;
  });
  const bool ks_zero = gbuffer.has_per_pixel_ks() ? all_zero(gbuffer.ks) : table_ks_zero;
  const bool specular = any_lights && !ks_zero;
  add_flag(recipe, "SPECULAR", specular,
           specular     ? "specular: compiled in (some material has ks > 0 or is principled)"
           : any_lights ? "specular: compiled out (every ks is 0): no pow"
                        : "specular: compiled out (no lights)",
           specular ? "specular" : "no specular");

  decide_specular_models(recipe, scene, gbuffer, specular);

  const bool table_ka_zero = std::all_of(materials.begin(), materials.end(), [](const Material& m) { return is_zero(m.ka); });
  const bool ka_zero = gbuffer.has_per_pixel_ka() ? all_zero(gbuffer.ka) : table_ka_zero;
  const bool ambient = !is_zero(scene.ambient) && !ka_zero;
  add_flag(recipe, "AMBIENT", ambient,
           ambient                  ? "ambient: compiled in"
           : is_zero(scene.ambient) ? "ambient: compiled out (ambient light is 0)"
                                    : "ambient: compiled out (every ka is 0)",
           ambient ? "ambient" : "no ambient");
}

// Needs recipe.lanes.
void decide_materials(Recipe& recipe, const Scene& scene, const GBuffer& gbuffer) {
  recipe.per_pixel_ka = gbuffer.has_per_pixel_ka();
  recipe.per_pixel_kd = gbuffer.has_per_pixel_kd();
  recipe.per_pixel_ks = gbuffer.has_per_pixel_ks();
  recipe.per_pixel_shininess = gbuffer.has_per_pixel_shininess();
  const bool table_needed = !(recipe.per_pixel_ka && recipe.per_pixel_kd && recipe.per_pixel_ks && recipe.per_pixel_shininess);
  const int count = static_cast<int>(scene.materials.size());
  const bool single = recipe.specialised && count <= 1;
  const bool selects = recipe.specialised && table_needed && !single && recipe.lanes > 1 && count <= recipe.lanes;
  const std::string table = !table_needed ? " (every coefficient is per pixel)" : "";
  add_flag(recipe, "SINGLE_MATERIAL", single,
           single ? "materials: single material, no per-pixel fetch" + table
                  : "materials: " + plural(count, "material") + " in a table" + table,
           single ? "single material" : selects ? "" : "material table");
  add_count(recipe, "MATERIAL_COUNT", selects ? count : 0,
            selects ? "materials: count compiled in (per-lane selects, no gather)"
            : single ? "materials: no table lookup"
                     : "materials: indexed per pixel" + std::string(recipe.lanes > 1 ? " (gathered)" : ""),
            selects ? "material table (selects)" : "");
  auto per_pixel = [&](const char* name, bool present, const std::string& what) {
    add_flag(recipe, name, present, what + (present ? ": per-pixel channel of the G-buffer" : ": from the material table"),
             present ? "per-pixel " + what : "");
  };
  per_pixel("PER_PIXEL_KA", recipe.per_pixel_ka, "Ka");
  per_pixel("PER_PIXEL_KD", recipe.per_pixel_kd, "Kd");
  per_pixel("PER_PIXEL_KS", recipe.per_pixel_ks, "Ks");
  per_pixel("PER_PIXEL_Q", recipe.per_pixel_shininess, "shininess");
}

// Soft shadows: lights with a size (area lights, spheres, suns with an angle) that cast them with
// more than one ray, traced against the geometry or marched across the depth plane.
// Without one, nothing of them is compiled in, and the hard shadows shade as before, bit for bit.
void decide_soft_shadows(Recipe& recipe, const Scene& scene) {
  int soft = 0, most_rays = 0;
  auto count = [&](bool shadows, int rays) {
    if (!shadows || rays < 2) return;
    ++soft;
    most_rays = std::max(most_rays, rays);
  };
  if (recipe.shadows == ShadowMode::geometry || recipe.shadows == ShadowMode::screen) {
    for (const Light& light : scene.lights) count(light.shadows, shadow_rays(light, recipe.shadow_settings));
    for (const AreaLight& light : scene.area_lights) count(light.shadows, shadow_rays(light, recipe.shadow_settings));
  }
  const std::string why = soft > 0 ? "soft shadows: " + plural(soft, "light") + " with a size, up to " +
                                         std::to_string(most_rays) + " rays each over the emitter"
                                   : "soft shadows: compiled out (no light with a size traces more than one ray)";
  add_flag(recipe, "SOFT_SHADOWS", soft > 0, why, soft > 0 ? "soft shadows (" + plural(soft, "light") + ")" : "");
}

// The environment's visibility: with a shadow mode on and "shadows" true, `rays` cosine-distributed
// rays per pixel, traced or marched as the mode says; else the unoccluded irradiance.
void decide_environment_shadows(Recipe& recipe, const Scene& scene) {
  recipe.environment_shadows = recipe.environment && scene.environment->shadows && recipe.shadows != ShadowMode::off;
  recipe.environment_rays = recipe.environment_shadows ? shadow_rays(*scene.environment, recipe.shadow_settings) : 0;
  const std::string rays = plural(recipe.environment_rays, "ray");
  add_flag(recipe, "ENVIRONMENT_SHADOWS", recipe.environment_shadows,
           recipe.environment_shadows ? "environment visibility: " + rays + " per pixel, " +
                                            (recipe.shadows == ShadowMode::screen ? "marched across the depth plane"
                                                                                  : "traced against the scene's objects")
           : recipe.environment ? "environment visibility: none (shadows off or the light's \"shadows\" false)"
                                : "environment visibility: compiled out (no environment)",
           recipe.environment_shadows ? "environment visibility (" + rays + ")" : "");
}

// Lights cast shadows when they ask ("shadows": true) and the mode is not off: auto traces the
// scene's objects when it has some, else marches across the G-buffer's depth. Decided by the scene
// in the general kernel too: without a light that casts them nothing of it is compiled in.
void decide_shadows(Recipe& recipe, const Scene& scene, const ShadeOptions& options) {
  const ShadowSettings& asked = options.shadows;
  check_shadow_settings(asked);
  recipe.shadow_settings = asked;
  recipe.shadow_casters = static_cast<int>(
      std::count_if(scene.lights.begin(), scene.lights.end(), [](const Light& light) { return light.shadows; }) +
      std::count_if(scene.area_lights.begin(), scene.area_lights.end(),
                    [](const AreaLight& light) { return light.shadows; }));
  const bool objects = !scene.objects.empty();
  // The environment's visibility rays need the shadow inputs as a light's shadow rays do.
  const bool environment_casts = scene.environment && scene.environment->shadows;
  const bool casting = recipe.shadow_casters > 0 || environment_casts;
  if (casting && asked.mode == ShadowMode::geometry && !objects)
    throw std::invalid_argument("shadows geometry: the scene has no objects to cast them (use screen or auto)");
  const ShadowMode mode = !casting || asked.mode == ShadowMode::off ? ShadowMode::off
                          : asked.mode == ShadowMode::automatic ? (objects ? ShadowMode::geometry : ShadowMode::screen)
                                                                : asked.mode;
  recipe.shadows = mode;
  const std::string casters = plural(recipe.shadow_casters, "light") + (environment_casts ? " + the environment" : "");
  const std::string march = std::to_string(asked.steps) + " steps, thickness " + format_shadow_thickness(asked.thickness);
  const std::string why = !casting ? "shadows: compiled out (no light casts them)"
                          : mode == ShadowMode::off  ? "shadows: compiled out (off as asked)"
                          : mode == ShadowMode::geometry
                              ? "shadows: " + casters + ", rays traced against the scene's objects (BVH)"
                              : "shadows: " + casters + ", marched across the G-buffer's depth (" + march + ")";
  const std::string chosen = asked.mode == ShadowMode::automatic ? (objects ? " (auto: the scene has objects)"
                                                                            : " (auto: the scene has no objects)")
                                                                 : "";
  add_flag(recipe, "SHADOWS", mode != ShadowMode::off, why + chosen,
           mode == ShadowMode::off ? "" : to_string(mode) + " shadows (" + casters + ")");
  add_flag(recipe, "SCREEN_SHADOWS", mode == ShadowMode::screen,
           mode == ShadowMode::screen ? "screen-space shadows: " + march : "screen-space shadows: none");
  decide_soft_shadows(recipe, scene);
  decide_environment_shadows(recipe, scene);
}

// Light groups are AOVs: their layers are written with the terms; without terms the kernel is the
// one without groups. The count is compiled in (the group loop unrolls), in the general kernel too.
void decide_groups(Recipe& recipe, const Scene& scene, const ShadeOptions& options) {
  const std::vector<std::string> groups = light_groups(scene.lights, scene.area_lights, scene.environment);
  if (options.write_terms) recipe.light_groups = groups;
  const int count = static_cast<int>(recipe.light_groups.size());
  add_count(recipe, "LIGHT_GROUPS", count,
            count > 0       ? "light groups: " + plural(count, "group") + ", each one's diffuse + specular written apart"
            : groups.empty() ? "light groups: none"
                             : "light groups: not written (" + plural(static_cast<int>(groups.size()), "group") +
                                   ", but no terms asked for)",
            count > 0 ? plural(count, "light group") : "");
}

// Area lights live in __global memory and are looped over untiled: a few rects and disks, each
// costing far more than its load.
void decide_area_lights(Recipe& recipe, const Scene& scene) {
  const auto disks = std::count_if(scene.area_lights.begin(), scene.area_lights.end(),
                                   [](const AreaLight& light) { return light.shape == AreaShape::disk; });
  recipe.area_lights = static_cast<int>(scene.area_lights.size());
  const int rects = recipe.area_lights - static_cast<int>(disks);
  std::string kinds;
  if (rects > 0) kinds = plural(rects, "rect");
  if (disks > 0) kinds += (kinds.empty() ? "" : " + ") + plural(static_cast<int>(disks), "disk");
  add_flag(recipe, "AREA_LIGHTS", recipe.area_lights > 0,
           recipe.area_lights > 0 ? "area lights: " + kinds + ", untiled (diffuse exact, specular by quadrature)"
                                  : "area lights: compiled out (none in the scene)",
           recipe.area_lights > 0 ? kinds + " area" : "");
}

// The world's light: its irradiance map read per pixel (kernels/environment.h).
void decide_environment(Recipe& recipe, const Scene& scene) {
  recipe.environment = scene.environment.has_value();
  const std::string kind = !recipe.environment ? ""
                           : scene.environment->file.empty() ? "uniform colour"
                                                             : "map " + scene.environment->file.filename().string();
  add_flag(recipe, "ENVIRONMENT", recipe.environment,
           recipe.environment ? "environment: " + kind +
                                    ", diffuse from its irradiance map, specular (with SPECULAR) from each lobe's prefiltered map"
                              : "environment: compiled out (none in the scene)",
           recipe.environment ? "environment (" + kind + ")" : "");
}

// Needs recipe.precision. Positions relative to the eye rounded to float lose a light near a
// surface far away (1e-4 from a surface 1e4 from the eye is 1e-8 of the position): with point or
// spot lights, positions and lights come as float pairs, value + rest. Decided by the scene in the
// general kernel too (it sets the planes packed). Half storage keeps 11 bits of a position, far
// fewer than a rest could restore, and is there to move fewer bytes.
void decide_position_rest(Recipe& recipe) {
  const bool half = recipe.precision == Precision::half_storage;
  recipe.position_rest = add_flag(recipe, "POSITION_REST", recipe.point_lights > 0 && !half,
                                  recipe.point_lights == 0 ? "position rests: none (no point or spot lights)"
                                  : half ? "position rests: none (half storage)"
                                         : "position rests: positions and point lights as float pairs (L - P to float "
                                           "precision near lights)");
}

void decide_memory(Recipe& recipe, const Scene& scene, const DeviceInfo& device) {
  // The scene block (phong_launch.h): every table, each from a multiple of kSceneTableAlignment. The
  // casters' and groups' words are counted whether or not the scene has them.
  const std::size_t lights = recipe.point_lights + recipe.directional_lights + scene.area_lights.size();
  const unsigned long long bytes = recipe.point_lights * sizeof(PointLight) +
                                   recipe.directional_lights * sizeof(DirectionalLight) +
                                   std::max<std::size_t>(scene.materials.size(), 1) * sizeof(MaterialRecord) +
                                   recipe.point_lights * sizeof(LightShape) +
                                   (recipe.point_lights + recipe.directional_lights) * recipe.link_words *
                                       sizeof(LinkWord) +
                                   scene.area_lights.size() * sizeof(AreaLightRecord) +
                                   2 * lights * sizeof(layout_uint) + kSceneTables * kSceneTableAlignment +
                                   (scene.environment ? sizeof(EnvironmentRecord) + sizeof(layout_uint) +
                                                            2 * 3 * kIrradianceWidth * kIrradianceHeight * sizeof(float) +  // E / pi and the sky
                                                            kMaxSunCells * sizeof(EnvironmentSun) +
                                                            (recipe.value("SPECULAR") == "1" ? environment_lobe_bytes(scene) : 0)
                                                      : 0);
  const bool constant = recipe.specialised && device.max_constant_args >= 1 && bytes <= device.max_constant_buffer;
  recipe.flags.push_back({"UNIFORM_SPACE", constant ? "__constant" : "__global",
                          constant ? "lights and materials: __constant memory (" + std::to_string(bytes) + " bytes fit)"
                                   : "lights and materials: __global memory",
                          ""});
}

}  // namespace

Culling parse_culling(const std::string& name) {
  if (name == "auto") return Culling::automatic;
  if (name == "tiled") return Culling::tiled;
  if (name == "none") return Culling::none;
  throw std::invalid_argument("unknown culling '" + name + "' (expected auto, tiled or none)");
}

int Recipe::plane_count() const {
  return PLANE_GEOMETRY_COUNT + 3 * (per_pixel_ka + per_pixel_kd + per_pixel_ks) + per_pixel_shininess + 3 * position_rest;
}

const std::string& Recipe::value(const std::string& name) const {
  for (const RecipeFlag& flag : flags)
    if (flag.name == name) return flag.value;
  throw std::out_of_range("the recipe has no flag " + name);
}

std::string Recipe::build_options() const {
  std::string options = "-cl-std=CL1.2";
  if (precision == Precision::fast) options += " -cl-fast-relaxed-math";
  for (const RecipeFlag& flag : flags) options += " -D" + flag.name + "=" + flag.value;
  return options;
}

std::vector<std::string> Recipe::reasons() const {
  std::vector<std::string> lines;
  for (const RecipeFlag& flag : flags) lines.push_back(flag.why + " [" + flag.name + "=" + flag.value + "]");
  return lines;
}

std::string Recipe::summary() const {
  std::string text = to_string(precision) + (specialised ? ", specialised" : ", general kernel");
  const char* separator = ": ";
  for (const RecipeFlag& flag : flags) {
    if (flag.summary.empty()) continue;
    text += separator + flag.summary;
    separator = ", ";
  }
  return text;
}

Recipe make_recipe(const Scene& scene, const GBuffer& gbuffer, const DeviceInfo& device, const ShadeOptions& options) {
  if (options.precision == Precision::double_precision && !device.has_fp64) {
    throw std::runtime_error("--precision double: device " + device.name + " has no fp64 support (cl_khr_fp64)");
  }
  Recipe recipe;
  recipe.specialised = options.specialise;
  count_lights(recipe, scene);
  decide_lanes(recipe, device, options);
  decide_precision(recipe, options.precision);
  decide_culling(recipe, scene, options);
  decide_lights(recipe);
  decide_light_shapes(recipe, scene);
  decide_area_lights(recipe, scene);
  decide_environment(recipe, scene);
  decide_terms(recipe, scene, gbuffer);
  decide_materials(recipe, scene, gbuffer);
  decide_position_rest(recipe);
  decide_memory(recipe, scene, device);
  decide_shadows(recipe, scene, options);
  recipe.write_terms = add_flag(recipe, "WRITE_TERMS", options.write_terms,
                                options.write_terms ? "terms: ambient, diffuse and specular also written apart (AOVs)"
                                                    : "terms: not written apart");
  decide_groups(recipe, scene, options);
  return recipe;
}

}  // namespace phongcl
