#pragma once
#include <string>

namespace phongcl {

// "CL_OUT_OF_RESOURCES (-5)": the symbolic name of an OpenCL error code, with the number.
std::string cl_error_name(int code);

}  // namespace phongcl
