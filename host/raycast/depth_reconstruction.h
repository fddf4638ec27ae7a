#pragma once
// Positions from a depth pass and the scene camera, for G-buffers that store depth instead of P.
#include "gbuffer/gbuffer.h"
#include "scene/scene.h"

namespace phongcl {

// What a depth value measures, for the surface point P seen through a pixel centre:
//   distance  |P - eye|: distance along the ray from the eye; P = eye + depth * unit ray direction.
//   view_z    dot(P - eye, forward): distance along the viewing axis, positive in front of the
//             camera (planar depth, -z of OpenGL view space); P = eye + depth * ray / dot(ray, forward).
// The two agree at the image centre and differ by 1/cos(angle off axis) towards the corners.
// Renderers differ (and have changed between versions) in which they write: say which with
// --depth-convention.
enum class DepthConvention { distance, view_z };

// Fills gbuffer.position from depth (one value per pixel, the G-buffer's data window) using the
// same pixel-centre rays as the generator (raycast/camera.h). Pixel (x, y) of the file is pixel
// (x - display.x_min, y - display.y_min) of the camera's image, so the display window must be the
// camera's width x height (InputError naming gbuffer.source otherwise). Background pixels
// (material < 0) get P = 0: their depth is often "infinitely far".
void positions_from_depth(GBuffer& gbuffer, const Plane& depth, const Camera& camera, DepthConvention convention);

}  // namespace phongcl
