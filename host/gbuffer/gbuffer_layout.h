#pragma once
// The phongcl G-buffer layout, stated once for reading and writing: which EXR channel fills which
// plane, and which groups of channels are required.
#include <type_traits>
#include <vector>

#include "gbuffer/gbuffer.h"

namespace phongcl {

template <class Plane>
struct LayoutChannel {
  const char* name;
  Plane* plane;
};

template <class Plane>
struct LayoutGroup {
  bool required;  // optional groups are used only when every channel of the group is present
  std::vector<LayoutChannel<Plane>> channels;
};

// Buffer is GBuffer (to fill) or const GBuffer (to write).
template <class Buffer>
auto gbuffer_layout(Buffer& g) {
  using P = std::remove_reference_t<decltype((g.material))>;  // Plane or const Plane
  auto rgb = [](const char* r, const char* gr, const char* b, auto& planes) {
    return std::vector<LayoutChannel<P>>{{r, &planes[0]}, {gr, &planes[1]}, {b, &planes[2]}};
  };
  return std::vector<LayoutGroup<P>>{
      {true, rgb("P.X", "P.Y", "P.Z", g.position)},
      {true, rgb("N.X", "N.Y", "N.Z", g.normal)},
      {true, {{"material", &g.material}}},
      {false, rgb("Ka.R", "Ka.G", "Ka.B", g.ka)},
      {false, rgb("Kd.R", "Kd.G", "Kd.B", g.kd)},
      {false, rgb("Ks.R", "Ks.G", "Ks.B", g.ks)},
      {false, {{"shininess", &g.shininess}}},
  };
}

}  // namespace phongcl
