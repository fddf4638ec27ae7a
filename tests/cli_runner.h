#pragma once
// Runs the real phongcl binary (PHONGCL_EXE) and captures what a user would see.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace phongcl::testing {

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A run still going after this long is killed (coreutils' timeout: exit status 124), so a phongcl
// that hangs fails its test instead of holding ctest for its 600 s.
inline constexpr int kRunLimitSeconds = 300;

// `arguments` is appended to the binary's path as shell words; `environment` (e.g. "FOO=1 ") is
// prefixed. Standard input is closed, as in CI.
inline CliRun run_phongcl(const std::string& arguments, const std::string& environment = "") {
  static int counter = 0;
  const auto base = std::filesystem::temp_directory_path() /
                    ("phongcl-cli-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  const std::string command = "cd '" PHONGCL_SOURCE_DIR "' && " + environment + "timeout -k 10 " +
                              std::to_string(kRunLimitSeconds) + " '" PHONGCL_EXE "' " + arguments +
                              " </dev/null >'" + base.string() + ".out' 2>'" + base.string() + ".err'";
  const int status = std::system(command.c_str());
  CliRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = read_text(base.string() + ".out");
  run.err = read_text(base.string() + ".err");
  std::filesystem::remove(base.string() + ".out");
  std::filesystem::remove(base.string() + ".err");
  return run;
}

// True where `phongcl devices` finds an OpenCL device; tests that shade report SKIP otherwise.
inline bool have_opencl_device() {
  static const bool found = run_phongcl("devices").exit_code == 0;
  return found;
}

}  // namespace phongcl::testing
