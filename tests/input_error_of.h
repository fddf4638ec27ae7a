#pragma once
// The message of the InputError an action throws, or "" when it throws none: for tests that look for
// a message's words (no error then fails their find()).
#include <functional>
#include <string>

#include "common/error.h"

namespace phongcl::testing {

inline std::string input_error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace phongcl::testing
