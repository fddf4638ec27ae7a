#pragma once
// Positions from a depth pass and the scene camera, for G-buffers that store depth instead of P.
#include "gbuffer/gbuffer.h"
#include "gbuffer/layouts.h"
#include "scene/scene.h"

namespace phongcl {

// DepthConvention (gbuffer/layouts.h) says what a depth value measures:
//   distance  P = eye + depth * unit ray direction.
//   view_z    P = eye + depth * ray / dot(ray, forward).
// Each layout has a default (Blender: view_z); --depth-convention overrides it.
// Fills gbuffer.position from depth (one value per pixel, the G-buffer's data window) using the
// same pixel-centre rays as the generator (raycast/camera.h). Pixel (x, y) of the file is pixel
// (x - display.x_min, y - display.y_min) of the camera's image, so the display window must be the
// camera's width x height (InputError naming gbuffer.source otherwise). Background pixels
// (material < 0) get P = 0: their depth is often "infinitely far".
void positions_from_depth(GBuffer& gbuffer, const Plane& depth, const Camera& camera, DepthConvention convention);

// The same for a G-buffer as read (its depth pass and convention), then the edge repair that
// waited for positions (GBufferRead::edges_need_positions).
void positions_from_depth(GBufferRead& read, const Camera& camera);

}  // namespace phongcl
