#include "stability/gbuffer_builder.h"

namespace phongcl {

GBuffer blank_gbuffer(int width, int height, const std::string& name) {
  GBuffer gbuffer;
  gbuffer.width = width;
  gbuffer.height = height;
  gbuffer.data_window = gbuffer.display_window = PixelWindow{0, 0, width - 1, height - 1};
  const std::size_t pixels = gbuffer.pixel_count();
  for (Planes3* planes : {&gbuffer.position, &gbuffer.normal}) {
    for (Plane& plane : *planes) plane.assign(pixels, 0.0f);
  }
  gbuffer.material.assign(pixels, -1.0f);
  gbuffer.source = name;
  return gbuffer;
}

void add_per_pixel_materials(GBuffer& gbuffer) {
  const std::size_t pixels = gbuffer.pixel_count();
  for (Planes3* planes : {&gbuffer.ka, &gbuffer.kd, &gbuffer.ks}) {
    for (Plane& plane : *planes) plane.assign(pixels, 0.0f);
  }
  gbuffer.shininess.assign(pixels, 0.0f);
}

void set_surface(GBuffer& gbuffer, std::size_t index, const glm::vec3& position, const glm::vec3& normal, float material) {
  for (int axis = 0; axis < 3; ++axis) {
    gbuffer.position[axis][index] = position[axis];
    gbuffer.normal[axis][index] = normal[axis];
  }
  gbuffer.material[index] = material;
}

void set_material(GBuffer& gbuffer, std::size_t index, float ka, float kd, float ks, float shininess) {
  for (int c = 0; c < 3; ++c) {
    gbuffer.ka[c][index] = ka;
    gbuffer.kd[c][index] = kd;
    gbuffer.ks[c][index] = ks;
  }
  gbuffer.shininess[index] = shininess;
}

}  // namespace phongcl
