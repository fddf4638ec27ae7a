#pragma once
// Kernel source text with its #include "..." lines resolved, from the embedded copies or, when
// PHONGCL_KERNEL_DIR is set, from that directory (for editing kernels without rebuilding).
#include <string>

namespace phongcl {

// Throws std::runtime_error if a file is missing. #line directives keep build-log line numbers
// pointing at the original files.
std::string load_kernel_source(const std::string& file_name);

}  // namespace phongcl
