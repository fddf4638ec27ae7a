#include "shading/pack.h"

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <sstream>
#include <thread>
#include <vector>

#include "common/error.h"
#include "common/host_threads.h"
#include "shading/light_order.h"
#include "shading/pack_area.h"
#include "shading/pack_environment_specular.h"
#include "shading/pack_principled_v2.h"
#include "shading/store3.h"

namespace phongcl {

using std::numbers::pi;

namespace {

// The Principled BSDF v1's record (kernels/principled.h; docs/shading.md "Principled", after Cycles
// 3.x's svm_node_closure): kd its diffuse weight base * (1 - metallic), ks the Fresnel's colour at
// normal incidence cspec0 = mix(0.08 specular mix(1, tint, specular_tint), base, metallic) with
// tint the base colour over its luminance 0.3 r + 0.6 g + 0.1 b, and the index the Fresnel remaps
// from, 2 / (1 - sqrt(0.08 specular)) - 1.
void store_principled(MaterialRecord& record, const Material& material) {
  const glm::dvec3 base = material.base_color;
  const double luminance = 0.3 * base.r + 0.6 * base.g + 0.1 * base.b;
  const glm::dvec3 tint = luminance > 0.0 ? base / luminance : glm::dvec3(1.0);
  const glm::dvec3 dielectric = 0.08 * material.specular * glm::mix(glm::dvec3(1.0), tint, material.specular_tint);
  store3(record.kd, base * (1.0 - material.metallic));
  store3(record.ks, glm::mix(dielectric, base, material.metallic));
  record.shininess = 1.0f;
  record.roughness = static_cast<float>(material.roughness);
  record.ior = static_cast<float>(2.0 / (1.0 - std::sqrt(0.08 * material.specular)) - 1.0);
}

// What rounding `value` to float loses.
float rest_of(double value) { return static_cast<float>(value - static_cast<double>(static_cast<float>(value))); }

double largest_component(const glm::dvec3& c) { return std::max({c.x, c.y, c.z}); }

const char* plane_name(const Recipe& recipe, int plane) {
  static const char* geometry[] = {"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z"};
  if (plane < PLANE_GEOMETRY_COUNT) return geometry[plane];
  static const char* ka[] = {"Ka.R", "Ka.G", "Ka.B"};
  static const char* kd[] = {"Kd.R", "Kd.G", "Kd.B"};
  static const char* ks[] = {"Ks.R", "Ks.G", "Ks.B"};
  int next = PLANE_GEOMETRY_COUNT;
  for (auto [present, names] : {std::pair{recipe.per_pixel_ka, ka}, {recipe.per_pixel_kd, kd}, {recipe.per_pixel_ks, ks}}) {
    if (!present) continue;
    if (plane < next + 3) return names[plane - next];
    next += 3;
  }
  return "shininess";
}

void append_link_mask(const Light& light, int words, std::vector<LinkWord>& links) {
  const std::size_t first = links.size();
  links.resize(first + static_cast<std::size_t>(words), light.materials ? 0u : ~0u);
  if (light.materials)
    for (int material : *light.materials)
      if (material >= 0 && material < 32 * words)  // an index beyond the table links nothing
        links[first + static_cast<std::size_t>(material / 32)] |= 1u << (material % 32);
}

}  // namespace

UniformData pack_uniforms(const Scene& scene, const Recipe& recipe) {
  UniformData data;
  double brightest = largest_component(scene.ambient);
  for (const Light& light : scene.lights) brightest = std::max(brightest, largest_component(light.color));
  brightest = std::max(brightest, brightest_area_light(scene));
  const std::shared_ptr<const IrradianceMap> irradiance = environment_irradiance(scene);
  brightest = std::max(brightest, brightest_environment(scene, *irradiance));
  // Scale so the brightest colour lands in [0.5, 1); split 2^e in two factors that are both normal floats.
  const int exponent = brightest > 0.0 ? std::ilogb(brightest) + 1 : 0;
  const double scale = std::ldexp(1.0, -exponent);
  data.scalars.radiance_scale_a = static_cast<float>(std::ldexp(1.0, exponent / 2));
  data.scalars.radiance_scale_b = static_cast<float>(std::ldexp(1.0, exponent - exponent / 2));

  const glm::dvec3& eye = scene.camera.eye;
  for (const Light& light : scene.lights) {
    if (light.type != LightType::directional) {
      PointLight packed{};
      const glm::dvec3 position = light.position - eye;
      store3(packed.position, position);
      for (int axis = 0; axis < 3; ++axis) packed.position_rest[axis] = rest_of(position[axis]);
      store3(packed.color, light.color * scale);
      data.point_lights.push_back(packed);
      data.point_shapes.push_back(light_shape(light));
      if (recipe.tiled) data.point_bounds.push_back(light_bounds(light, eye));
    } else {
      DirectionalLight packed{};
      store3(packed.to_light, -glm::normalize(light.direction));
      store3(packed.color, light.color * scale);
      data.directional_lights.push_back(packed);
    }
  }
  // Linking masks in the kernel's order: point and spot lights first, then directional ones.
  if (recipe.link_words > 0)
    for_each_light_in_kernel_order(scene.lights, [&](const Light& light) {
      append_link_mask(light, recipe.link_words, data.links);
    });
  // Light groups, the area lights' then the environment's last; a light in none gets the group count.
  if (!recipe.light_groups.empty()) {
    const auto& groups = recipe.light_groups;
    auto index = [&](const std::string& group) {
      return static_cast<layout_uint>(std::find(groups.begin(), groups.end(), group) - groups.begin());
    };
    for_each_light_in_kernel_order(scene.lights, [&](const Light& light) { data.light_groups.push_back(index(light.group)); });
    for (const AreaLight& light : scene.area_lights) data.light_groups.push_back(index(light.group));
    if (scene.environment) data.light_groups.push_back(index(scene.environment->group));
  }
  for (const Material& material : scene.materials) {
    MaterialRecord record{};
    store3(record.ka, material.ka);
    store3(record.kd, material.kd);
    store3(record.ks, material.ks);
    record.shininess = static_cast<float>(material.shininess);
    record.specular_model = static_cast<float>(kernel_specular_model(material.specular_model, material.version));
    if (material.specular_model == SpecularModel::principled)
      material.version == 2 ? store_principled_v2(record, material) : store_principled(record, material);
    data.materials.push_back(record);
  }
  for (int c = 0; c < 3; ++c) {
    data.scalars.ambient[c] = static_cast<float>(scene.ambient[c] * scale);
    data.scalars.background[c] = static_cast<float>(scene.background[c]);
  }
  data.scalars.point_count = static_cast<layout_int>(data.point_lights.size());
  data.scalars.directional_count = static_cast<layout_int>(data.directional_lights.size());
  data.area_lights = pack_area_lights(scene, scale);
  data.scalars.area_count = static_cast<layout_int>(data.area_lights.size());
  data.environment = pack_environment(scene, *irradiance, recipe.environment_rays, scale);
  if (recipe.environment && recipe.value("SPECULAR") == "1") pack_environment_lobes(data.environment, scene, irradiance);
  return data;
}

// For a spot: a sphere around its cone cut by the range (for a half angle t up to 45 degrees the
// sphere through apex and rim, radius R / (2 cos t); wider, the rim's circle, radius R sin t).
LightShape light_shape(const Light& light) {
  LightShape shape{};
  static_assert(static_cast<int>(Falloff::cubic) == PHONGCL_MAX_FALLOFF, "the kernel unrolls the powers up to cubic");
  shape.falloff = static_cast<int>(light.falloff);
  shape.inverse_range = light.has_range() ? static_cast<float>(1.0 / light.range) : 0.0f;
  shape.versine_inner = shape.versine_outer = 3.0f;  // a point light: every direction is inside
  if (light.type == LightType::spot) {
    store3(shape.axis, glm::normalize(light.direction));
    // 1 - cos(t) = 2 sin^2(t / 2): no cancellation for narrow cones.
    auto versine = [](double angle) { return 2.0 * std::sin(angle / 2.0) * std::sin(angle / 2.0); };
    const double half_angle = light.cone_angle_deg / 2.0 * pi / 180.0;
    const double inner = versine(half_angle), outer = versine(half_angle + light.penumbra_angle_deg * pi / 180.0);
    shape.versine_inner = static_cast<float>(inner);
    shape.versine_outer = light.penumbra_angle_deg > 0.0 ? static_cast<float>(outer) : shape.versine_inner;
    shape.inverse_cone_width = light.penumbra_angle_deg > 0.0 ? static_cast<float>(1.0 / (outer - inner)) : 0.0f;
    // Beyond float's largest the power is that: c^p is then 1 on the axis and 0 off it all the same.
    shape.cosine_power = static_cast<float>(std::min<double>(light.cosine_power, std::numeric_limits<float>::max()));
  }
  return shape;
}

namespace {

// The distance bins (layout.h) of every distance from the eye in [nearest, farthest], and one more
// each way, which covers the rounding of the positions' float distances.
cl_uint distance_bins(double nearest, double farthest) {
  const auto bin = [](double distance) {
    const float distance_sq = static_cast<float>(distance * distance);
    cl_uint bits;
    std::memcpy(&bits, &distance_sq, sizeof bits);
    return static_cast<std::int64_t>(bits >> PHONGCL_DISTANCE_BIN_SHIFT);
  };
  const std::int64_t first = bin(std::max(nearest, 0.0)) - 1, last = bin(farthest) + 1;
  if (last - first >= 31) return ~cl_uint{0};
  const cl_uint span = (cl_uint{2} << (last - first)) - 1;  // last - first + 1 bits
  const auto rotation = static_cast<unsigned>(first & 31);
  return rotation == 0 ? span : (span << rotation) | (span >> (32 - rotation));
}

}  // namespace

LightBounds light_bounds(const Light& light, const glm::dvec3& eye) {
  LightBounds bounds{};
  const glm::dvec3 position = light.position - eye;
  const bool spot = light.type == LightType::spot;
  // A spot's outer half angle (the cone and its penumbra) and its axis.
  const double half_angle = spot ? (light.cone_angle_deg / 2.0 + light.penumbra_angle_deg) * pi / 180.0 : 0.0;
  const glm::dvec3 axis = spot ? glm::normalize(light.direction) : glm::dvec3(0.0);
  // A spot with a radius whose shadow is soft takes its cone from every point of its emitter
  // (soft_shadow.h): every such cone lies in the one of the same angle whose apex is r / sin(angle)
  // behind the centre. Its range (from the centre) is then bounded by the range's ball alone.
  const bool wide_cone = spot && light.radius > 0.0;
  const glm::dvec3 apex = wide_cone ? position - light.radius / std::sin(std::max(half_angle, 1e-6)) * axis : position;
  glm::dvec3 center = position;
  double radius = light.has_range() ? light.range : -1.0;
  if (spot && light.has_range() && !wide_cone) {
    const double narrow = light.range / (2.0 * std::cos(half_angle));
    if (half_angle <= pi / 4.0) {
      center += narrow * axis;
      radius = narrow;
    } else {
      center += light.range * std::cos(half_angle) * axis;
      radius = light.range * std::sin(half_angle);
    }
  }
  store3(bounds.center, center);
  const double distance = glm::length(center);
  bounds.radius = radius < 0.0 ? -1.0f : static_cast<float>(radius + 1e-5 * (radius + distance));
  bounds.distance_bins = radius < 0.0 ? ~cl_uint{0} : distance_bins(distance - bounds.radius, distance + bounds.radius);
  bounds.cone_cos = -1.0f;
  // The kernel's cone test rounds its cosine to about 1e-6, an angle of up to 1.5e-3 radians at the
  // axis: the culling cone is 2e-3 wider, and nothing is tested past 89 degrees.
  const double culling_half_angle = half_angle + 2e-3;
  if (spot && culling_half_angle < 89.0 * pi / 180.0) {
    store3(bounds.apex, apex);
    store3(bounds.axis, axis);
    bounds.cone_cos = static_cast<float>(std::cos(culling_half_angle));
    bounds.cone_sin = static_cast<float>(std::sin(culling_half_angle));
  }
  return bounds;
}

void PixelCounts::add(PixelClass pixel_class) {
  switch (pixel_class) {
    case PixelClass::shaded: ++shaded; break;
    case PixelClass::background: ++background; break;
    case PixelClass::nonfinite_position: ++nonfinite_position; break;
    case PixelClass::nonfinite_normal: ++nonfinite_normal; break;
    case PixelClass::nonfinite_material: ++nonfinite_material; break;
  }
}

PixelCounts& PixelCounts::operator+=(const PixelCounts& other) {
  shaded += other.shaded;
  background += other.background;
  nonfinite_position += other.nonfinite_position;
  nonfinite_normal += other.nonfinite_normal;
  nonfinite_material += other.nonfinite_material;
  return *this;
}

namespace {

// Packs tile slots [begin, end): pixel first + t goes to slot t of every plane.
PixelCounts pack_range(const GBuffer& gbuffer, const glm::dvec3& eye, const Recipe& recipe, std::size_t first,
                       std::size_t begin, std::size_t end, std::size_t stride, float* planes,
                       std::int32_t* material_index) {
  std::vector<PixelClass> classes(end - begin);
  classify_pixels(gbuffer, first + begin, end - begin, classes.data());
  PixelCounts counts;
  for (std::size_t t = begin; t < end; ++t) {
    const PixelClass pixel_class = classes[t - begin];
    counts.add(pixel_class);
    material_index[t] =
        pixel_class == PixelClass::shaded ? static_cast<std::int32_t>(gbuffer.material[first + t]) : PHONGCL_BACKGROUND;
  }
  // With position rests they follow every other plane.
  const int rest_plane = recipe.plane_count() - 3;
  for (int axis = 0; axis < 3; ++axis) {
    float* position = planes + (PLANE_PX + axis) * stride;
    float* rest = planes + (rest_plane + axis) * stride;
    const float* source_position = gbuffer.position[axis].data() + first;
    const double eye_axis = eye[axis];
    for (std::size_t t = begin; t < end; ++t) {
      const double relative = static_cast<double>(source_position[t]) - eye_axis;
      position[t] = static_cast<float>(relative);
      if (recipe.position_rest) rest[t] = rest_of(relative);
    }
  }
  float* next_plane = planes + PLANE_NX * stride;
  auto copy_plane = [&](const Plane& channel) {
    std::copy(channel.data() + first + begin, channel.data() + first + end, next_plane + begin);
    next_plane += stride;
  };
  for (const Plane& channel : gbuffer.normal) copy_plane(channel);
  if (recipe.per_pixel_ka) for (const Plane& channel : gbuffer.ka) copy_plane(channel);
  if (recipe.per_pixel_kd) for (const Plane& channel : gbuffer.kd) copy_plane(channel);
  if (recipe.per_pixel_ks) for (const Plane& channel : gbuffer.ks) copy_plane(channel);
  if (recipe.per_pixel_shininess) copy_plane(gbuffer.shininess);
  // Unshaded slots get P = N = 0: a ray miss's Inf would send its whole vector down the kernel's
  // rescaling branch for every point light, and -cl-fast-relaxed-math assumes finite values.
  if (counts.shaded != end - begin) {
    for (std::size_t t = begin; t < end; ++t) {
      if (material_index[t] != PHONGCL_BACKGROUND) continue;
      for (int plane = PLANE_PX; plane < PLANE_GEOMETRY_COUNT; ++plane) planes[plane * stride + t] = 0.0f;
      if (recipe.position_rest)
        for (int axis = 0; axis < 3; ++axis) planes[(rest_plane + axis) * stride + t] = 0.0f;
    }
  }
  return counts;
}

}  // namespace

PixelCounts pack_tile(const GBuffer& gbuffer, const glm::dvec3& eye, const Recipe& recipe, std::size_t first,
                      std::size_t count, std::size_t padded_count, std::size_t stride, float* planes,
                      std::int32_t* material_index) {
  // Packing is part of every frame's end-to-end time: spread it over the cores in chunks large
  // enough that the threads stream whole cache lines.
  constexpr std::size_t kChunk = 1 << 15;
  std::vector<PixelCounts> part_counts(std::thread::hardware_concurrency() + 1);
  for_each_core_range(count, kChunk, [&](std::size_t part, std::size_t begin, std::size_t end) {
    part_counts[part] = pack_range(gbuffer, eye, recipe, first, begin, end, stride, planes, material_index);
  });
  PixelCounts counts;
  for (const PixelCounts& part : part_counts) counts += part;
  std::fill(material_index + count, material_index + padded_count, PHONGCL_BACKGROUND);
  for (int plane = 0; plane < recipe.plane_count(); ++plane) {
    std::fill(planes + plane * stride + count, planes + plane * stride + padded_count, 0.0f);
  }
  return counts;
}

std::size_t convert_planes_to_half(const GBuffer& gbuffer, const Recipe& recipe, std::size_t first, std::size_t count,
                                   std::size_t stride, float* planes, std::uint16_t* half_planes) {
  constexpr float kHalfMax = 65504.0f;
  constexpr float kHalfSmallest = 5.9604645e-8f;  // 2^-24, the smallest half subnormal
  // One range of pixels per core: Imath's conversion is some 3 ns a value, 40 ms a 1080p frame on one.
  std::vector<std::size_t> flushed(std::thread::hardware_concurrency() + 1, 0);
  for_each_core_range(count, 1024, [&](std::size_t part, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      float* x = planes + PLANE_NX * stride + t;
      float* y = planes + PLANE_NY * stride + t;
      float* z = planes + PLANE_NZ * stride + t;
      const float largest = std::max({std::fabs(*x), std::fabs(*y), std::fabs(*z)});
      if (largest > 0.0f && std::isfinite(largest)) {
        *x /= largest;
        *y /= largest;
        *z /= largest;
      }
    }
    for (int plane = 0; plane < recipe.plane_count(); ++plane) {
      const float* in = planes + plane * stride;
      std::uint16_t* out = half_planes + plane * stride;
      for (std::size_t t = begin; t < end; ++t) {
        const float value = in[t];
        const float magnitude = std::fabs(value);
        if (magnitude > kHalfMax && std::isfinite(value)) {
          const std::size_t i = first + t;
          std::ostringstream problem;
          problem << "--precision half-storage: " << plane_name(recipe, plane)
                  << (plane < 3 ? " (relative to the eye)" : "") << " value " << value << " at pixel ("
                  << gbuffer.data_window.x_min + static_cast<int>(i % gbuffer.width) << ", "
                  << gbuffer.data_window.y_min + static_cast<int>(i / gbuffer.width)
                  << ") exceeds half's range (65504); use --precision precise";
          throw InputError(gbuffer.source, problem.str());
        }
        if (magnitude > 0.0f && magnitude < kHalfSmallest / 2) ++flushed[part];
        out[t] = Imath::half(value).bits();
      }
    }
  });
  std::size_t total = 0;
  for (std::size_t part : flushed) total += part;
  return total;
}

}  // namespace phongcl
