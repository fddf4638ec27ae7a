#pragma once
// The kernel's variants a caller chooses: speed/precision (docs/shading.md "Precision variants") and light culling.
#include <string>
#include <vector>

namespace phongcl {

enum class Precision {
  double_precision,  // fp64 arithmetic where the device has cl_khr_fp64
  precise,           // float, IEEE semantics (the default)
  fast,              // float under -cl-fast-relaxed-math
  half_storage,      // G-buffer stored as half in device memory (half the bytes moved), float math
};

const std::vector<Precision>& all_precisions();
std::string to_string(Precision precision);
// Accepts the names to_string gives; throws std::invalid_argument listing them otherwise.
Precision parse_precision(const std::string& name);

// Tiled light culling: automatic (tiled when it pays, see make_recipe), or forced on or off.
enum class Culling { automatic, tiled, none };
Culling parse_culling(const std::string& name);  // "auto", "tiled", "none"; throws std::invalid_argument
// Culling::automatic culls per tile from this many point and spot lights with a range.
inline constexpr int kAutoCullingLights = 64;

}  // namespace phongcl
