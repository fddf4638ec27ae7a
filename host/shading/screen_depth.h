#pragma once
// What screen-space shadows march across (kernels/shadow.h): the frame's depth plane (the view depth
// of each pixel's surface, relative to the eye, +Inf where there is none) and the camera that
// projects an eye-relative point onto it (ScreenMarch, kernels/shadow_layout.h).
#include <vector>

#include "gbuffer/gbuffer.h"
#include "scene/scene.h"

extern "C" {
#include "kernels/shadow_layout.h"
}

namespace phongcl {

struct ScreenDepth {
  ScreenMarch march{};
  std::vector<float> depth;  // the G-buffer's data window, row by row
};

// `camera` is the one that rendered the G-buffer (the scene's, or the file's): its display window
// is the camera's image. Throws InputError naming the G-buffer when the camera does not put the
// G-buffer's positions on their own pixels (more than 1.5 pixels off at a sample of them), since the
// march would then read the wrong pixels; and when there is no shaded pixel, nothing to march over.
ScreenDepth screen_depth(const Camera& camera, const GBuffer& gbuffer, int steps, float thickness);

}  // namespace phongcl
