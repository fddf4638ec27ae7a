#pragma once
// The many-lights benchmark's lights: deterministic, spread through the volume of the G-buffer's
// shaded positions, with ranges sized so a shaded pixel is reached by a chosen number on average.
#include "gbuffer/gbuffer.h"
#include "scene/scene.h"

namespace phongcl {

// The scene with its lights replaced by `count` lights, alternately point and spot (cones of 60 to
// 120 degrees with a 10 degree penumbra, aimed downwards), quadratic falloff, coloured in varying
// hues, placed on a low-discrepancy sequence through the box of the shaded positions (raised a
// little so that floors are lit). Every light gets the same range, found by bisection so that
// about `target_reach` lights reach an average shaded pixel (d < range; the spot's cone
// counted too), measured on a sample of pixels. Throws std::invalid_argument for count < 1 or a
// G-buffer with no shaded pixel.
Scene with_many_lights(const Scene& scene, const GBuffer& gbuffer, int count, double target_reach = 30.0);

// How many of the scene's point and spot lights reach an average shaded pixel (d < range, inside a
// spot's outer cone; lights without a range always count), on every `step`-th shaded pixel.
double mean_lights_reaching(const Scene& scene, const GBuffer& gbuffer, std::size_t step = 1);

// How many of them reach at least one shaded pixel of an average shaded pixel's tile_size x
// tile_rows screen tile: the fewest lights per pixel that one list per tile can keep.
double mean_lights_reaching_tiles(const Scene& scene, const GBuffer& gbuffer, int tile_size, int tile_rows);

}  // namespace phongcl
