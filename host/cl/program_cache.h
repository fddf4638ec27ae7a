#pragma once
// Built OpenCL programs, cached in memory for this process and as program binaries on disk, keyed by
// device, driver, source and build options, so a second run of the same scene does not recompile.
#include <filesystem>
#include <map>
#include <string>

#include "cl/cache_outcome.h"
#include "cl/compute_context.h"

namespace phongcl {

struct BuiltProgram {
  cl::Program program;
  CacheOutcome outcome = CacheOutcome::compiled;
  double build_milliseconds = 0.0;  // compile, or load from binary
};

class ProgramCache {
 public:
  // `disk_directory` empty: memory only.
  explicit ProgramCache(std::filesystem::path disk_directory);

  // $PHONGCL_CACHE_DIR, else $XDG_CACHE_HOME/phongcl, else $HOME/.cache/phongcl; empty (no disk
  // cache) when none can be created and written, e.g. HOME unset or read-only.
  static std::filesystem::path default_directory();

  // Throws cl::BuildError (carrying the build log) when the source does not compile.
  BuiltProgram build(const ComputeContext& compute, const std::string& source, const std::string& options);

  const std::filesystem::path& disk_directory() const { return disk_directory_; }
  // Why the last disk write or read failed, if it did (the build itself still succeeded).
  const std::string& disk_problem() const { return disk_problem_; }

 private:
  std::map<std::string, cl::Program> memory_;
  std::filesystem::path disk_directory_;
  std::string disk_problem_;
};

}  // namespace phongcl
