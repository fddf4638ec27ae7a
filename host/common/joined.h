#pragma once
// Lists of names in messages: "a, b, c".
#include <string>
#include <string_view>
#include <vector>

namespace phongcl {

// `names` with `separator` between them, or `if_none` when there are none (an error message reads
// "found: none" better than "found: ").
std::string joined(const std::vector<std::string>& names, std::string_view separator = ", ",
                   std::string_view if_none = "");

}  // namespace phongcl
