#pragma once
// The stability catalogue: named stiff and extreme cases, each with its expected value and a
// tolerance per precision variant. docs/shading.md "Stiff and extreme inputs" states the policies.
#include <filesystem>
#include <vector>

#include "stability/stability_case.h"

namespace phongcl {

std::vector<StabilityCase> stability_catalogue();

// The groups, each in its own file.
std::vector<StabilityCase> stiff_exponent_cases();   // catalogue_stiff.cpp
std::vector<StabilityCase> geometry_cases();         // catalogue_geometry.cpp: grazing, degenerate, far, near lights
std::vector<StabilityCase> range_cases();            // catalogue_range.cpp: HDR, half, many lights, non-finite
std::vector<StabilityCase> light_shape_cases();      // catalogue_lights.cpp: falloff, range window, spots, linking
std::vector<StabilityCase> specular_model_cases();   // catalogue_specular.cpp: the lobes other than Phong's
std::vector<StabilityCase> area_light_cases();       // catalogue_area.cpp: rects and disks at their limits
std::vector<StabilityCase> principled_cases();       // catalogue_principled.cpp: both versions at their inputs' limits
// catalogue_shadows.cpp: lights on surfaces and inside objects, grazing rays, coincident triangles,
// degenerate and huge meshes, 1e6 from the origin; mesh files are written to `scratch`.
std::vector<StabilityCase> shadow_cases(const std::filesystem::path& scratch);

}  // namespace phongcl
