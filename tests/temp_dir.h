#pragma once
// A fresh directory per test under the system temp directory, removed afterwards.
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <system_error>

namespace phongcl::testing {

struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& suite) {
    static std::atomic<int> counter{0};
    path = std::filesystem::temp_directory_path() /
           ("phongcl_test_" + suite + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path / name; }
};

}  // namespace phongcl::testing
