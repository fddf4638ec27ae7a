#pragma once
// The environment light into the kernel's tables (kernels/layout.h EnvironmentRecord): its
// irradiance map (host/environment/) and the rotation from eye-relative directions into the map's frame.
#include <vector>

#include "environment/irradiance_map.h"
#include "scene/scene.h"
#include "shading/device_layout.h"

namespace phongcl {

// The scene's environment's irradiance map: the file's (cached, environment/irradiance_map.h) or a
// uniform colour's; with no environment an empty map. Throws InputError for a bad file.
std::shared_ptr<const IrradianceMap> environment_irradiance(const Scene& scene);

// The brightest E / pi or sky texel (bounded: the larger of the map's and the sky's brightest, plus
// every sun's) times the strength, for the radiance scale; 0 without an environment.
double brightest_environment(const Scene& scene, const IrradianceMap& irradiance);

// One record (none without an environment), whose scale is `scale` * strength, and the map's texels.
struct PackedEnvironment {
  std::vector<EnvironmentRecord> record;
  std::vector<layout_float> texels;
  std::vector<EnvironmentSun> suns;  // directions turned into the eye's frame
  std::vector<EnvironmentLobe> lobes;  // per material, with SPECULAR (pack_environment_specular.h)
};
PackedEnvironment pack_environment(const Scene& scene, const IrradianceMap& irradiance, int rays, double scale);

}  // namespace phongcl
