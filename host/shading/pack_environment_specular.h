#pragma once
// The environment's specular lobes into the kernel's tables (kernels/layout.h EnvironmentLobe): one
// per material, each pointing at the prefiltered map of its lobe (host/environment/prefiltered_map.h),
// one map per distinct lobe of the scene, appended to the environment's texels.
#include <memory>
#include <vector>

#include "environment/irradiance_map.h"
#include "environment/prefiltered_map.h"
#include "scene/scene.h"
#include "shading/device_layout.h"
#include "shading/pack_environment.h"

namespace phongcl {

// Distinct lobes that get a map of their own; a material whose lobe comes later takes the map of the
// nearest of them in width (lobe_width), with its own integral and cosine: its highlight as bright
// as its own, as sharp as that map's.
inline constexpr int kMaxEnvironmentLobes = 16;

// The material's lobe: its model's (specular.h numbers), from its shininess or Principled roughness.
SpecularLobe environment_lobe(const Material& material);

// The bytes the scene's maps take (the distinct lobes' prefiltered_height), without computing them.
std::size_t environment_lobe_bytes(const Scene& scene);

// Appends the distinct lobes' maps to packed.texels and one EnvironmentLobe per material to packed.lobes.
void pack_environment_lobes(PackedEnvironment& packed, const Scene& scene, const std::shared_ptr<const IrradianceMap>& map);

}  // namespace phongcl
