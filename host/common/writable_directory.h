#pragma once
#include <filesystem>

namespace phongcl {

// Creates `directory` (and its parents) if missing; true when it then exists and is writable.
// Cache directories use this: when it says no, the caller runs without that cache.
bool ensure_writable_directory(const std::filesystem::path& directory);

}  // namespace phongcl
