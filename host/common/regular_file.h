#pragma once
// An input that must be a regular file, refused for what it is otherwise: missing, a directory, a
// FIFO or device (which would block or never end), a symbolic-link loop.
#include <filesystem>
#include <string>

namespace phongcl {

// Throws InputError naming `file`: "cannot read the <kind>: " and "no such file", "it is a
// directory", "it is not a regular file" or the system's reason ("Too many levels of symbolic links").
void require_regular_file(const std::filesystem::path& file, const std::string& kind);

}  // namespace phongcl
