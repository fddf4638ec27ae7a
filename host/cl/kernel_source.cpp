#include "cl/kernel_source.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "cl/embedded_kernels.h"

namespace phongcl {

namespace {

std::string read_kernel_file(const std::string& name) {
  if (const char* dir = std::getenv("PHONGCL_KERNEL_DIR")) {
    const std::filesystem::path path = std::filesystem::path(dir) / name;
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path.string() + ": cannot read kernel file (PHONGCL_KERNEL_DIR is set)");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  const auto& files = embedded_kernel_files();
  const auto found = files.find(name);
  if (found == files.end()) throw std::runtime_error("kernel file '" + name + "' is not embedded in this build");
  return std::string(found->second);
}

// Inlines each header once, as a compiler's include guard would.
void append_resolved(const std::string& name, std::set<std::string>& included, std::string& out) {
  if (!included.insert(name).second) return;
  static const std::regex include_line(R"re(^\s*#\s*include\s*"([^"]+)"\s*$)re");
  std::istringstream lines(read_kernel_file(name));
  std::string line;
  int number = 0;
  out += "#line 1 \"" + name + "\"\n";
  while (std::getline(lines, line)) {
    ++number;
    std::smatch match;
    if (std::regex_match(line, match, include_line)) {
      append_resolved(match[1].str(), included, out);
      out += "#line " + std::to_string(number + 1) + " \"" + name + "\"\n";
    } else {
      out += line + "\n";
    }
  }
}

}  // namespace

std::string load_kernel_source(const std::string& file_name) {
  std::set<std::string> included;
  std::string out;
  append_resolved(file_name, included, out);
  return out;
}

}  // namespace phongcl
