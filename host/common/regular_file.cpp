#include "common/regular_file.h"

#include "common/error.h"

namespace phongcl {

void require_regular_file(const std::filesystem::path& file, const std::string& kind) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(file, error);
  const std::string cannot = "cannot read the " + kind + ": ";
  if (status.type() == std::filesystem::file_type::not_found) throw InputError(file, cannot + "no such file");
  if (error) throw InputError(file, cannot + error.message());
  if (std::filesystem::is_directory(status)) throw InputError(file, cannot + "it is a directory");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(file, cannot + "it is not a regular file (a FIFO, device or socket)");
}

}  // namespace phongcl
