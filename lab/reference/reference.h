#pragma once
// The scalar reference: the Phong formula in double precision, written from the specification
// (docs/shading.md "The formula"), single-threaded and plain. It checks the OpenCL kernel, so it
// shares no code with kernels/ or host/shading/.
#include <functional>

#include <glm/glm.hpp>

#include "gbuffer/gbuffer.h"
#include "image/image.h"
#include "scene/scene.h"

namespace phongcl {

// One shaded surface point, material already resolved (table or per-pixel).
struct SurfacePoint {
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0};  // any length; normalised here
  glm::dvec3 ka{0.0}, kd{0.0}, ks{0.0};
  double shininess = 1.0;
  SpecularModel specular_model = SpecularModel::phong;  // the table's (a G-buffer has no model channel)
  Material principled{};  // with specular_model principled, the table's material (its inputs)
  int material = 0;  // the table index, for light linking
};

// The three terms of L_o separately; total() is their sum.
struct ShadingTerms {
  glm::dvec3 ambient{0.0}, diffuse{0.0}, specular{0.0};
  glm::dvec3 total() const { return ambient + diffuse + specular; }
};

// Whether a light that casts shadows reaches a point (lab/reference/reference_shadows.h decides it
// by brute force, reference_screen_shadows.h by the march); empty: every light reaches everything.
using LightReach = std::function<bool(const SurfacePoint& point, const Light& light)>;
// Soft shadows: the visible fraction of a light's emitter from a point, which its light is multiplied
// by (reference_soft_shadows.h). Where set, they decide the lights that cast shadows, not LightReach:
// `area` every area light, `sized` point, spot and directional lights with a size.
// `environment`: the environment's light over the directions nothing blocks, for kd = 1
// (reference_environment.h), where it casts shadows.
struct SoftVisibility {
  std::function<double(const SurfacePoint& point, const AreaLight& light)> area;
  std::function<double(const SurfacePoint& point, const Light& light)> sized;
  std::function<glm::dvec3(const SurfacePoint& point)> environment{};
};

// A spot's cone(l) for unit l from the surface towards it: the smoothstep of its penumbra (a step
// without one) times max(0, c)^p, c the cosine to its axis.
double reference_spot_cone(const Light& light, const glm::dvec3& l);

// What the specular term takes from a light of unit colour and F = 1 per unit ks, for unit n, v and
// l with n.l > 0 (docs/shading.md "Specular models"): max(0, v.r)^q or max(0, n.h)^q, the
// normalised models times their factor and n.l. pow(0, 0) = 1; l + v = 0 has no half vector: n.h = 0.
double reference_specular_lobe(SpecularModel model, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l,
                               double shininess);

ShadingTerms reference_shade_point(const Scene& scene, const SurfacePoint& point, const LightReach& reaches = {},
                                   const SoftVisibility& soft = {});

// The material of a shaded pixel: per-pixel channels where present, else the scene's table.
SurfacePoint reference_surface(const Scene& scene, const GBuffer& gbuffer, std::size_t index);

// Each term's own image, premultiplied as the whole image is (0 where nothing is shaded).
struct ReferenceTermImages {
  Image ambient, diffuse, specular;
};

// The whole image: shaded pixels get total() (alpha 1), the rest the scene background (alpha 0);
// with `terms`, each term's image too.
Image reference_image(const Scene& scene, const GBuffer& gbuffer, const LightReach& reaches = {},
                      const SoftVisibility& soft = {}, ReferenceTermImages* terms = nullptr);

// The scene lit by one light group alone (`group` empty: the ungrouped lights), point, spot,
// directional and area lights alike, with no ambient: its reference_image() is that group's layer
// (docs/shading.md "Light groups").
Scene reference_group_scene(const Scene& scene, const std::string& group);

}  // namespace phongcl
