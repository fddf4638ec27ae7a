#pragma once
// The throughput sweep's inputs: a scene with a given number of lights, and a G-buffer at a given
// size. Both deterministic, so every implementation and every run shades the same frame.
#include "gbuffer/gbuffer.h"
#include "image/image.h"
#include "scene/scene.h"

namespace phongcl {

// The scene with its lights replaced by `count` lights: (count + 1) / 2 point lights on a
// hemisphere above camera.look_at (radius 1.5 x the eye's distance) and count / 2 directional
// lights shining down from hemisphere directions, both on a golden-angle spiral so that any count
// spreads evenly; colours vary in hue and sum to about 2 whatever the count. Throws
// std::invalid_argument for a negative count.
Scene with_generated_lights(const Scene& scene, int count);

// Nearest-neighbour resample of every channel to width x height (pixel centres map to the source
// pixel that contains them); windows become [0, width-1] x [0, height-1]. Material indices and
// background pixels are copied, never blended. Throws std::invalid_argument for a size < 1.
GBuffer resample_nearest(const GBuffer& gbuffer, int width, int height);

// Rows 0, step, 2 step, ... of a G-buffer or an image, for measuring on a sample of a frame too
// large to shade whole with a slow implementation (the scalar peer, the double reference).
// Throws std::invalid_argument for step < 1.
GBuffer every_nth_row(const GBuffer& gbuffer, int step);
Image every_nth_row(const Image& image, int step);

}  // namespace phongcl
