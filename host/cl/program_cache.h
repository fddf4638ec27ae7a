#pragma once
// Built OpenCL programs, cached in memory for this process and as program binaries on disk, keyed by
// device, driver, source and build options, so a second run of the same scene does not recompile.
// Both caches are bounded and drop the program used longest ago: a server that meets a new light
// count on every edit keeps the last ones it used, not every one (each holds a megabyte or two of
// compiled code in memory and about 100 KB on disk).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <list>
#include <string>
#include <unordered_map>
#include <utility>

#include "cl/cache_outcome.h"
#include "cl/compute_context.h"

namespace phongcl {

struct BuiltProgram {
  cl::Program program;
  CacheOutcome outcome = CacheOutcome::compiled;
  double build_milliseconds = 0.0;  // compile, or load from binary
};

struct ProgramCacheLimits {
  std::size_t memory_programs = 32;           // in this process
  std::size_t disk_files = 256;               // in the disk directory (shared by every process)
  std::uintmax_t disk_bytes = std::uintmax_t{128} << 20;
};

class ProgramCache {
 public:
  // `disk_directory` empty: memory only.
  explicit ProgramCache(std::filesystem::path disk_directory, ProgramCacheLimits limits = {});

  // $PHONGCL_CACHE_DIR, else $XDG_CACHE_HOME/phongcl, else $HOME/.cache/phongcl; empty (no disk
  // cache) when none can be created and written, e.g. HOME unset or read-only.
  static std::filesystem::path default_directory();

  // Throws cl::BuildError (carrying the build log) when the source does not compile.
  BuiltProgram build(const ComputeContext& compute, const std::string& source, const std::string& options);

  const std::filesystem::path& disk_directory() const { return disk_directory_; }
  // Why the last disk write or read failed, if it did (the build itself still succeeded).
  const std::string& disk_problem() const { return disk_problem_; }
  std::size_t programs_in_memory() const { return memory_.size(); }

 private:
  using Entries = std::list<std::pair<std::string, cl::Program>>;  // most recently used first
  void remember(const std::string& key, const cl::Program& program);
  // Removes the binaries used longest ago (by modification time, which a hit renews) until the
  // directory is within the limits.
  void trim_disk();

  ProgramCacheLimits limits_;
  Entries memory_;
  std::unordered_map<std::string, Entries::iterator> index_;
  std::filesystem::path disk_directory_;
  std::string disk_problem_;
};

}  // namespace phongcl
