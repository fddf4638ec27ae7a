#pragma once
// Errors the user can fix: bad files, bad flags, a missing device. Library code throws these;
// only the CLI's main() turns them into a one-line message and an exit code.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace phongcl {

// A problem with an input file, named in the message: "<file>: <problem>".
class InputError : public std::runtime_error {
 public:
  InputError(const std::filesystem::path& file, const std::string& problem)
      : std::runtime_error(file.string() + ": " + problem) {}
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace phongcl
