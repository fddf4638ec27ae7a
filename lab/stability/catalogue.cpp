#include "stability/catalogue.h"

namespace phongcl {

std::vector<StabilityCase> stability_catalogue() {
  std::vector<StabilityCase> cases;
  for (auto* group : {&stiff_exponent_cases, &geometry_cases, &range_cases, &light_shape_cases, &specular_model_cases, &area_light_cases,
                      &principled_cases}) {
    for (StabilityCase& c : group()) cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace phongcl
