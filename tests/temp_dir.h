#pragma once
// A fresh directory per test under the system temp directory, removed afterwards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <string>
#include <system_error>

namespace phongcl::testing {

// "Suite.Name" of the running test ('/' of parameterised tests as '_'), for names that say who made them.
inline std::string running_test_name() {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = test ? std::string(test->test_suite_name()) + "." + test->name() : "outside_a_test";
  std::replace(name.begin(), name.end(), '/', '_');
  return name;
}

struct TempDir {
  std::filesystem::path path;
  TempDir() : TempDir(running_test_name()) {}
  explicit TempDir(const std::string& name) {
    static std::atomic<int> counter{0};
    path = std::filesystem::temp_directory_path() /
           ("phongcl_test_" + name + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
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
