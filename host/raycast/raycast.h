#pragma once
// The G-buffer generator: a perspective ray caster for the scene's objects (spheres, planes,
// triangles under nested transforms), one primary ray through each pixel centre.
#include "gbuffer/gbuffer.h"
#include "scene/scene.h"

namespace phongcl {

// Pixels whose ray hits nothing get material -1 (background), P = N = 0.
// Normals are unit length, world space, facing the side the ray came from.
GBuffer generate_gbuffer(const Scene& scene);

}  // namespace phongcl
