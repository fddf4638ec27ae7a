#pragma once
// The kernels/ files, embedded at build time by cmake/WriteEmbeddedKernels.cmake.
#include <map>
#include <string>
#include <string_view>

namespace phongcl {

// File name (e.g. "phong.cl", "layout.h") to its text.
const std::map<std::string, std::string_view>& embedded_kernel_files();

}  // namespace phongcl
