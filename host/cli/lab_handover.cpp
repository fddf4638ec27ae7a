#include "cli/lab_handover.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

namespace phongcl::cli {

namespace {

constexpr const char* kLabCommands[] = {"reference", "compare", "bench", "stability", "agreement"};

}  // namespace

bool is_lab_command(const std::string& name) {
  for (const char* command : kLabCommands)
    if (name == command) return true;
  return false;
}

int hand_over_to_lab(char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path lab = self.parent_path() / "phongcl-lab";
  if (!ec && std::filesystem::exists(lab, ec)) {
    execv(lab.c_str(), argv);
    std::cerr << "phongcl: cannot run " << lab.string() << ": " << std::strerror(errno) << "\n";
    return 1;
  }
  std::cerr << "phongcl: '" << argv[1] << "' is a lab command, in phongcl-lab, which is not installed beside "
            << (ec ? std::string("this phongcl") : self.string())
            << " (build from source with -DPHONGCL_BUILD_LAB=ON, the default)\n";
  return 1;
}

std::string lab_commands_note() {
  return "Lab commands (reference, compare, bench, stability, agreement) run phongcl-lab, built with the lab "
         "(-DPHONGCL_BUILD_LAB=ON) and not installed.";
}

}  // namespace phongcl::cli
