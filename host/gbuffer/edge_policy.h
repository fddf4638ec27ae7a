#pragma once
// What renderers' files hold at the edges of surfaces, and how phongcl reads it (docs/formats.md
// "Edges"). A renderer takes position, depth and the index passes from one sample near the pixel
// centre but filters normal and colour passes over the pixel's footprint, where sky samples add
// nothing: at an edge the normal and colours are the surface's scaled by the fraction of samples
// that hit it.
#include <cstddef>

#include "gbuffer/gbuffer.h"

namespace phongcl {

// Marks background (material -1) every pixel whose centre sample hit nothing: a depth that is not
// finite or at least no_hit_depth, or, with no depth plane, a position of exactly (0, 0, 0).
// Returns how many pixels that made background which were not background already.
std::size_t mark_sky_samples(GBuffer& gbuffer, const Plane& depth, float no_hit_depth);

enum class CoverageSource {
  none,           // every surface pixel fully covered
  alpha,          // a transparent film's alpha
  normal_length,  // an opaque film: the filtered normal's length, on pixels next to background
};
const char* coverage_source_name(CoverageSource source);  // for the summary

// Fills gbuffer.coverage for shaded pixels (left empty when every one is 1): the alpha plane where
// some shaded pixel has 0 < alpha < 1, else min(1, |N|) on shaded pixels with a background pixel
// among their 8 neighbours (between two surfaces the filtered normal is short because it averages
// two directions, not because anything is uncovered). Divides the per-pixel kd and ks by it, since
// they are filtered like the normal.
CoverageSource estimate_coverage(GBuffer& gbuffer, const Plane& alpha);

// Between two surfaces the filtered normal averages both (up to 80 degrees off the centre
// sample's surface) and the colour passes mix both materials. A shaded pixel not next to the
// background whose normal is shorter than 0.98 (a spread of about 16 degrees or more) takes the
// normal and colours of the neighbour that lies on the centre sample's surface: among the 8
// neighbours of the same material with an unmixed normal, the one whose tangent plane passes
// closest to this pixel's position. Returns how many pixels were repaired. Call after
// estimate_coverage (which reads the lengths next to the background).
std::size_t repair_surface_edges(GBuffer& gbuffer);

}  // namespace phongcl
