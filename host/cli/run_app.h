#pragma once
// The one top-level try of a phongcl command line: library code throws, only here is an error
// printed and an exit code chosen (0, 1 for a failure, 2 for bad usage).
#include <CLI/CLI.hpp>

namespace phongcl::cli {

int run_app(CLI::App& app, int argc, char** argv);

}  // namespace phongcl::cli
