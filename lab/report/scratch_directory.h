#pragma once
// A private temporary directory for a benchmark's generated inputs, removed with everything in it
// when the benchmark ends (also by an exception).
#include <filesystem>
#include <string>
#include <system_error>

#include <unistd.h>

namespace phongcl {

class ScratchDirectory {
 public:
  // <temp>/<prefix>-<pid>
  explicit ScratchDirectory(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace phongcl
