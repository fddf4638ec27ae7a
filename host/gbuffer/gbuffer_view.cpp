// make_gbuffer: the caller's strided channels gathered into phongcl's planes.
#include <phongcl/gbuffer_view.hpp>

#include <stdexcept>
#include <string>

namespace phongcl {

namespace {

Plane gather(const ChannelView& view, int width, int height) {
  const std::ptrdiff_t row_stride = view.row_stride != 0 ? view.row_stride : width * view.pixel_stride;
  Plane plane(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    const float* row = view.data + y * row_stride;
    float* out = plane.data() + static_cast<std::size_t>(y) * width;
    for (int x = 0; x < width; ++x) out[x] = row[x * view.pixel_stride];
  }
  return plane;
}

// An empty group stays empty (the table applies); a partial one is an error.
Planes3 gather3(const Vec3View& view, int width, int height, const char* name, bool required) {
  const int present = (view.x.data != nullptr) + (view.y.data != nullptr) + (view.z.data != nullptr);
  if (present == 3) return {gather(view.x, width, height), gather(view.y, width, height), gather(view.z, width, height)};
  if (present == 0 && !required) return {};
  std::string problem = "GBufferView: ";
  problem += name;
  problem += present == 0 ? " is required" : " needs all three channels";
  throw std::invalid_argument(problem);
}

}  // namespace

GBuffer make_gbuffer(const GBufferView& view) {
  if (view.width < 1 || view.height < 1)
    throw std::invalid_argument("GBufferView: size " + std::to_string(view.width) + "x" +
                                std::to_string(view.height) + " (must be at least 1x1)");
  if (view.material.data == nullptr) throw std::invalid_argument("GBufferView: material is required");
  const int w = view.width, h = view.height;
  GBuffer g;
  g.width = w;
  g.height = h;
  g.data_window = g.display_window = PixelWindow{0, 0, w - 1, h - 1};
  g.position = gather3(view.position, w, h, "position", true);
  g.normal = gather3(view.normal, w, h, "normal", true);
  g.material = gather(view.material, w, h);
  if (view.alpha.data != nullptr) {
    const Plane alpha = gather(view.alpha, w, h);
    for (std::size_t i = 0; i < alpha.size(); ++i)
      if (alpha[i] == 0.0f) g.material[i] = -1.0f;
  }
  g.ka = gather3(view.ka, w, h, "ka", false);
  g.kd = gather3(view.kd, w, h, "kd", false);
  g.ks = gather3(view.ks, w, h, "ks", false);
  if (view.shininess.data != nullptr) g.shininess = gather(view.shininess, w, h);
  g.source = "<caller's arrays>";
  return g;
}

}  // namespace phongcl
