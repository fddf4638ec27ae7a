#pragma once
// The stability catalogue: named stiff and extreme cases, each with its expected value and a
// tolerance per precision variant. docs/shading.md "Stiff and extreme inputs" states the policies.
#include <vector>

#include "stability/stability_case.h"

namespace phongcl {

std::vector<StabilityCase> stability_catalogue();

// The groups, each in its own file.
std::vector<StabilityCase> stiff_exponent_cases();   // catalogue_stiff.cpp
std::vector<StabilityCase> geometry_cases();         // catalogue_geometry.cpp: grazing, degenerate, far
std::vector<StabilityCase> range_cases();            // catalogue_range.cpp: HDR, half, many lights, non-finite
std::vector<StabilityCase> light_shape_cases();      // catalogue_lights.cpp: falloff, range window, spots, linking

}  // namespace phongcl
