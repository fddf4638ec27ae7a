#include "common/atomic_file.h"

#include <unistd.h>

#include <string>
#include <system_error>

#include "common/error.h"

namespace phongcl {

namespace fs = std::filesystem;

void write_atomically(const fs::path& destination, const std::function<void(const fs::path&)>& write) {
  // Same directory as the destination so the final rename cannot cross file systems. The temporary
  // keeps the destination's extension: some writers (OpenEXR, PNG) look at it.
  const fs::path temp = destination.parent_path() /
                        ("." + destination.stem().string() + ".tmp" + std::to_string(::getpid()) +
                         destination.extension().string());
  try {
    write(temp);
    std::error_code ec;
    fs::rename(temp, destination, ec);
    if (ec) throw InputError(destination, "cannot write: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

}  // namespace phongcl
