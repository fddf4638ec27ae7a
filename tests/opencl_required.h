#pragma once
// What a test that needs an OpenCL device does on a machine without one. A local run reports SKIP
// and says why; under CI (the CI environment variable set, as .ci/run and CI services set it) the
// test FAILS, so that a broken OpenCL install cannot pass as a green run of skipped kernel tests.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string_view>

namespace phongcl::testing {

inline bool running_in_ci() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && *ci != '\0' && std::string_view(ci) != "false" && std::string_view(ci) != "0";
}

}  // namespace phongcl::testing

// In a TEST body or SetUp: PHONGCL_REQUIRE_OPENCL(found); returns from it, with SKIP locally and FAIL
// under CI, unless `found` (a device, or what was made from one) holds.
#define PHONGCL_REQUIRE_OPENCL(found)                                                             \
  if (found) {                                                                                   \
  } else if (::phongcl::testing::running_in_ci())                                                \
    GTEST_FAIL() << "no OpenCL device, and CI is set: the OpenCL install is broken";             \
  else                                                                                           \
    GTEST_SKIP() << "no OpenCL device on this machine (a run with CI set fails here)"
