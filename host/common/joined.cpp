#include "common/joined.h"

namespace phongcl {

std::string joined(const std::vector<std::string>& names, std::string_view separator, std::string_view if_none) {
  if (names.empty()) return std::string(if_none);
  std::string text = names.front();
  for (std::size_t i = 1; i < names.size(); ++i) (text += separator) += names[i];
  return text;
}

}  // namespace phongcl
