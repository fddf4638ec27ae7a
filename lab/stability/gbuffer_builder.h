#pragma once
// Small G-buffers built in memory, pixel by pixel, for the catalogue and the accuracy bars.
#include <cstddef>
#include <string>

#include <glm/glm.hpp>

#include "gbuffer/gbuffer.h"

namespace phongcl {

// width x height pixels, all background (material -1) at the origin with zero normals.
GBuffer blank_gbuffer(int width, int height, const std::string& name);

// Gives every pixel a per-pixel material (Ka, Kd, Ks, shininess planes), all zero.
void add_per_pixel_materials(GBuffer& gbuffer);

// Stores P, N and the material index of pixel `index` as the floats the file would hold.
void set_surface(GBuffer& gbuffer, std::size_t index, const glm::vec3& position, const glm::vec3& normal,
                 float material = 0.0f);

// Per-pixel Ka, Kd, Ks (grey) and shininess; the G-buffer must have per-pixel materials.
void set_material(GBuffer& gbuffer, std::size_t index, float ka, float kd, float ks, float shininess);

}  // namespace phongcl
