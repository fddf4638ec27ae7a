#include "peers/peers.h"
#include "peers/phong_pixel.h"

namespace phongcl {

// One pixel at a time. GCC leaves it scalar: the light loops are float reductions it may not
// reorder without -ffast-math, and nothing asks it to vectorise across pixels.
void shade_scalar(const PackedFrame& frame, const PackedScene& scene, float* rgba) {
  using namespace peer_math;
  const FrameView f = view_of(frame);
  const SceneView s = view_of(scene);
  for (std::size_t i = 0; i < frame.pixels; ++i) {
    const Vec3 p{f.px[i], f.py[i], f.pz[i]};
    const Vec3 n = unit_or_zero({f.nx[i], f.ny[i], f.nz[i]});
    const Vec3 v = unit_or_zero({-p.x, -p.y, -p.z});  // the eye is the origin
    const float q = s.shininess[f.material[i]];
    LightSums sums;
    for (int k = 0; k < s.point_count; ++k) {
      const Vec3 l = unit_or_zero(Vec3{s.point_x[k], s.point_y[k], s.point_z[k]} - p);
      sums.add(s.point_r[k], s.point_g[k], s.point_b[k], light_term(n, v, l, q));
    }
    for (int k = 0; k < s.directional_count; ++k) {
      sums.add(s.dir_r[k], s.dir_g[k], s.dir_b[k], light_term(n, v, {s.dir_x[k], s.dir_y[k], s.dir_z[k]}, q));
    }
    write_pixel(s, f.material[i], sums, rgba + 4 * i);
  }
}

}  // namespace phongcl
