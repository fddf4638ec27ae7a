#pragma once
// The one place the OpenCL C++ bindings are included (CMake sets CL_HPP_* for every target).
#include <CL/opencl.hpp>
