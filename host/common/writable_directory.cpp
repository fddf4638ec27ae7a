#include "common/writable_directory.h"

#include <unistd.h>

#include <system_error>

namespace phongcl {

bool ensure_writable_directory(const std::filesystem::path& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  return !ec && ::access(directory.c_str(), W_OK) == 0;
}

}  // namespace phongcl
