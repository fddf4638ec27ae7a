#pragma once
// The page's files (web/*), embedded at build time by cmake/EmbedKernels.cmake's generator.
#include <map>
#include <string>
#include <string_view>

namespace phongcl {

const std::map<std::string, std::string_view>& embedded_web_files();

}  // namespace phongcl
