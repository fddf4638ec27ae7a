#pragma once
// `phongcl reference|compare|bench|stability ...` runs phongcl-lab from phongcl's own directory, so
// the product binary links none of the lab and the commands keep their names. An installed
// phongcl has no lab beside it, and says so.
#include <string>

namespace phongcl::cli {

bool is_lab_command(const std::string& name);
// Replaces this process with phongcl-lab (same arguments); returns an exit code only on failure.
int hand_over_to_lab(char** argv);
std::string lab_commands_note();  // for --help

}  // namespace phongcl::cli
