#include "peers/packed_frame.h"

#include <cmath>

#include "common/error.h"
#include "shading/pack.h"

namespace phongcl {

PackedFrame pack_frame(const GBuffer& gbuffer, const Scene& scene) {
  if (gbuffer.has_per_pixel_ka() || gbuffer.has_per_pixel_kd() || gbuffer.has_per_pixel_ks() ||
      gbuffer.has_per_pixel_shininess()) {
    throw InputError(gbuffer.source, "the C++ peers shade from the material table; per-pixel material channels are not supported");
  }
  check_materials(gbuffer, scene.materials.size());
  for (const Material& m : scene.materials)
    if (m.specular_model != SpecularModel::phong)
      throw InputError(scene.source, "the C++ peers shade Phong's lobe; material '" + m.name + "' asks for " +
                                         to_string(m.specular_model));
  PackedFrame frame;
  frame.pixels = gbuffer.pixel_count();
  const std::size_t padded = (frame.pixels + kPeerPadding - 1) / kPeerPadding * kPeerPadding;
  AlignedVector<float>* positions[] = {&frame.px, &frame.py, &frame.pz};
  AlignedVector<float>* normals[] = {&frame.nx, &frame.ny, &frame.nz};
  for (int axis = 0; axis < 3; ++axis) {
    positions[axis]->resize(padded);
    normals[axis]->resize(padded);
  }
  frame.material.resize(padded, kPeerBackground);
  const glm::dvec3& eye = scene.camera.eye;
  for (std::size_t i = 0; i < frame.pixels; ++i) {
    if (classify_pixel(gbuffer, i) != PixelClass::shaded) continue;  // P and N stay 0: finite, no light
    frame.material[i] = static_cast<std::int32_t>(gbuffer.material[i]);
    for (int axis = 0; axis < 3; ++axis) {
      (*positions[axis])[i] = static_cast<float>(static_cast<double>(gbuffer.position[axis][i]) - eye[axis]);
      (*normals[axis])[i] = gbuffer.normal[axis][i];
    }
  }
  return frame;
}

namespace {

// The shape and the culling sphere as the OpenCL path packs them (shading/pack.h).
void pack_shape(const Light& light, const glm::dvec3& eye, PackedScene& packed) {
  const LightShape shape = light_shape(light);
  const LightBounds bounds = light_bounds(light, eye);
  for (auto [plane, value] :
       {std::pair{&packed.falloff_power, static_cast<float>(shape.falloff)}, {&packed.inverse_range, shape.inverse_range},
        {&packed.axis_x, shape.axis[0]}, {&packed.axis_y, shape.axis[1]}, {&packed.axis_z, shape.axis[2]},
        {&packed.versine_inner, shape.versine_inner}, {&packed.versine_outer, shape.versine_outer},
        {&packed.inverse_cone_width, shape.inverse_cone_width}, {&packed.bound_x, bounds.center[0]},
        {&packed.bound_y, bounds.center[1]}, {&packed.bound_z, bounds.center[2]}, {&packed.bound_radius, bounds.radius}}) {
    plane->push_back(value);
  }
}

}  // namespace

PackedScene pack_scene(const Scene& scene) {
  PackedScene packed;
  auto add_material = [&](const glm::dvec3& ambient, const glm::dvec3& kd, const glm::dvec3& ks, double q, float alpha) {
    for (auto [plane, value] : {std::pair{&packed.ambient_r, ambient.r}, {&packed.ambient_g, ambient.g},
                                {&packed.ambient_b, ambient.b}, {&packed.kd_r, kd.r}, {&packed.kd_g, kd.g},
                                {&packed.kd_b, kd.b}, {&packed.ks_r, ks.r}, {&packed.ks_g, ks.g}, {&packed.ks_b, ks.b},
                                {&packed.shininess, q}}) {
      plane->push_back(static_cast<float>(value));
    }
    packed.alpha.push_back(alpha);
  };
  add_material(scene.background, glm::dvec3(0.0), glm::dvec3(0.0), 0.0, 0.0f);
  for (const Material& m : scene.materials) add_material(m.ka * scene.ambient, m.kd, m.ks, m.shininess, 1.0f);
  for (const Light& light : scene.lights) {
    const glm::dvec3 color = light.color;
    packed.linking |= light.materials.has_value();
    if (light.type != LightType::directional) {
      const glm::dvec3 p = light.position - scene.camera.eye;
      for (auto [plane, value] : {std::pair{&packed.point_x, p.x}, {&packed.point_y, p.y}, {&packed.point_z, p.z},
                                  {&packed.point_r, color.r}, {&packed.point_g, color.g}, {&packed.point_b, color.b}}) {
        plane->push_back(static_cast<float>(value));
      }
      pack_shape(light, scene.camera.eye, packed);
    } else {
      const glm::dvec3 l = -glm::normalize(light.direction);
      for (auto [plane, value] : {std::pair{&packed.dir_x, l.x}, {&packed.dir_y, l.y}, {&packed.dir_z, l.z},
                                  {&packed.dir_r, color.r}, {&packed.dir_g, color.g}, {&packed.dir_b, color.b}}) {
        plane->push_back(static_cast<float>(value));
      }
    }
  }
  return packed;
}

}  // namespace phongcl
