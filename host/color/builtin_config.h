#pragma once
// The config phongcl uses when none is named: made with OpenColorIO's API, no files. Its sRGB
// display has the three views phongcl's PNGs had before OCIO, each an sRGB encoding after a tone
// curve of the exposed linear value x:
//   reinhard  x / (1 + x)                                              (the default)
//   aces      Narkowicz's 2015 fit of the ACES filmic curve, clamped to [0, 1]
//   clamp     min(x, 1)
// Negative values display as 0 and +Inf as 1. Working space (scene_linear): linear Rec.709 (sRGB
// primaries, D65), with ACEScg, ACES2065-1, CIE XYZ (D65), encoded sRGB and Raw beside it.
#include <OpenColorIO/OpenColorIO.h>

namespace phongcl {

inline constexpr const char* kBuiltinWorkingSpace = "Linear Rec.709 (sRGB)";

OCIO_NAMESPACE::ConstConfigRcPtr make_builtin_config();

// The tone curves of the built-in views, in double, before the sRGB encoding: the definitions the
// views' tables are filled from (and the tests' oracle).
double reinhard_curve(double x);
double aces_fit_curve(double x);

}  // namespace phongcl
