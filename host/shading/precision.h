#pragma once
// The kernel's speed/precision variants (README "Precision variants").
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

}  // namespace phongcl
