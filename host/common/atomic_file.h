#pragma once
// Writing outputs without ever leaving a half-written or clobbered file behind.
#include <filesystem>
#include <functional>

namespace phongcl {

// Calls write(temp) with a temporary path in the destination's directory, then renames the
// temporary over destination. If write throws, the temporary is removed and destination is
// untouched; the exception propagates.
void write_atomically(const std::filesystem::path& destination,
                      const std::function<void(const std::filesystem::path& temp)>& write);

}  // namespace phongcl
