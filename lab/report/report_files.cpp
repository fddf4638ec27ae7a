#include "report/report_files.h"

#include <fstream>
#include <stdexcept>
#include <system_error>

#include "common/atomic_file.h"
#include "common/error.h"

namespace phongcl {

void create_report_directory(const std::filesystem::path& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec || !std::filesystem::is_directory(directory))
    throw std::runtime_error("cannot create report directory " + directory.string() + ": " +
                             (ec ? ec.message() : std::string("a file of that name exists")));
}

void write_text_file(const std::filesystem::path& file, const std::string& text) {
  write_atomically(file, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw InputError(file, "cannot write");
  });
}

}  // namespace phongcl
