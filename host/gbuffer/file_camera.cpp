#include "gbuffer/file_camera.h"

#include <ImfMatrixAttribute.h>
#include <ImfStandardAttributes.h>

#include <cmath>

#include "common/error.h"
#include "exr/exr_channels.h"

namespace phongcl {

namespace {

using Vector = Imath::V3d;

std::array<double, 3> to_array(const Vector& v) { return {v.x, v.y, v.z}; }

// p * m for a point (w = 1), divided by w.
Vector project(const Vector& p, const Imath::M44d& m) {
  Vector out;
  m.multVecMatrix(p, out);  // divides by w
  return out;
}

}  // namespace

std::optional<FileCamera> read_file_camera(const std::filesystem::path& file) {
  exr::InputExr input(file);
  const Imf::Header& header = input.header(0);
  if (!Imf::hasWorldToCamera(header) || !Imf::hasWorldToNDC(header)) return std::nullopt;
  const Imath::M44d world_to_camera(Imf::worldToCamera(header));
  const Imath::M44d world_to_ndc(Imf::worldToNDC(header));
  const double determinant = world_to_camera.determinant();
  if (!std::isfinite(determinant) || std::abs(determinant) < 1e-12)
    throw InputError(file, "worldToCamera is singular: it states no camera");
  const Imath::M44d camera_to_world = world_to_camera.inverse();
  const Imath::M44d camera_to_ndc = camera_to_world * world_to_ndc;  // row vectors: first to world

  FileCamera camera;
  const PixelWindow display = input.display_window();
  camera.width = display.width();
  camera.height = display.height();
  const Vector eye = project({0, 0, 0}, camera_to_world);
  Vector forward, up;
  camera_to_world.multDirMatrix(Vector(0, 0, 1), forward);
  camera_to_world.multDirMatrix(Vector(0, 1, 0), up);
  camera.eye = to_array(eye);
  camera.forward = to_array(forward.normalized());
  camera.up = to_array(up.normalized());

  // The axis meets NDC (0.5, 0.5); a point one unit up (right) at unit depth lands at
  // 0.5 - 1 / (2 tan(fov_y / 2)) in y (0.5 + 1 / (2 tan(fov_x / 2)) in x).
  const Vector centre = project({0, 0, 1}, camera_to_ndc);
  const Vector above = project({0, 1, 1}, camera_to_ndc);
  const Vector right = project({1, 0, 1}, camera_to_ndc);
  if (!(std::abs(centre.x - 0.5) < 1e-4 && std::abs(centre.y - 0.5) < 1e-4))
    throw InputError(file, "worldToNDC puts the camera's axis at NDC (" + std::to_string(centre.x) + ", " +
                               std::to_string(centre.y) + "), not the image centre: a lens shift phongcl's camera cannot represent");
  const double tan_half_y = 1.0 / (2.0 * (0.5 - above.y)), tan_half_x = 1.0 / (2.0 * (right.x - 0.5));
  if (!(tan_half_y > 0.0 && tan_half_x > 0.0))
    throw InputError(file, "worldToNDC does not look along worldToCamera's +z with y down in the image");
  const double aspect = double(camera.width) / camera.height;
  if (std::abs(tan_half_x / tan_half_y - aspect) > 1e-3 * aspect)
    throw InputError(file, "worldToNDC's horizontal and vertical fields of view imply non-square pixels for the " +
                               std::to_string(camera.width) + "x" + std::to_string(camera.height) + " display window");
  camera.fov_y_deg = 2.0 * std::atan(tan_half_y) * 180.0 / M_PI;
  return camera;
}

}  // namespace phongcl
