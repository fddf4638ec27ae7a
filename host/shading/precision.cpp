#include "shading/precision.h"

#include <stdexcept>

namespace phongcl {

const std::vector<Precision>& all_precisions() {
  static const std::vector<Precision> all{Precision::double_precision, Precision::precise, Precision::fast,
                                          Precision::half_storage};
  return all;
}

std::string to_string(Precision precision) {
  switch (precision) {
    case Precision::double_precision: return "double";
    case Precision::precise: return "precise";
    case Precision::fast: return "fast";
    case Precision::half_storage: return "half-storage";
  }
  return "?";
}

Precision parse_precision(const std::string& name) {
  for (Precision precision : all_precisions()) {
    if (to_string(precision) == name) return precision;
  }
  throw std::invalid_argument("unknown precision '" + name + "' (expected double, precise, fast or half-storage)");
}

}  // namespace phongcl
