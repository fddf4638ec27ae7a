#pragma once
// One estimate of what shading a frame holds, checked before it is allocated (common/memory_limit.h):
// the G-buffer packed for the device, the image and the terms' and light groups' images on both
// sides, and the shadow geometry with every mesh counted per instance.
#include <vector>

#include "common/memory_limit.h"
#include "gbuffer/gbuffer.h"
#include "scene/scene.h"
#include "shading/recipe.h"

namespace phongcl {

// The frame's own needs, which change with the lights (their groups) and the terms.
std::vector<MemoryNeed> frame_memory_needs(const GBuffer& gbuffer, const Recipe& recipe);

// The shadow geometry's, when the recipe traces the scene's objects; the mesh files' counts are read
// here (count_mesh), each file once.
std::vector<MemoryNeed> geometry_memory_needs(const Scene& scene, const Recipe& recipe);

// Throws std::runtime_error naming the largest need when all of them exceed memory_limit().
void check_frame_memory(const std::vector<MemoryNeed>& frame, const std::vector<MemoryNeed>& geometry);

}  // namespace phongcl
