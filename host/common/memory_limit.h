#pragma once
// What this process may still allocate, and one check of a task's estimated needs against it, so
// that a scene too large for the machine is one line naming what takes the memory, before the
// allocations, rather than std::bad_alloc (or the kernel's OOM killer) half-way through.
#include <cstdint>
#include <string>
#include <vector>

namespace phongcl {

struct MemoryLimit {
  std::uint64_t bytes = 0;
  std::string source;  // "the machine's available memory", "the address-space limit (ulimit -v)"
};

// The smaller of the machine's available memory (MemAvailable) and what the address-space limit
// leaves this process (RLIMIT_AS less what it maps now).
MemoryLimit memory_limit();

struct MemoryNeed {
  std::string what;  // "light groups (250 x 320x240 pixels)"
  double bytes = 0;
};

// Throws std::runtime_error when the needs together exceed `limit`, naming the total, the
// largest need and the limit's source: "`task` needs about 7.4 GB, most of it for ..., more than
// the 3.0 GB of the address-space limit (ulimit -v)".
void check_memory(const std::string& task, const std::vector<MemoryNeed>& needs, const MemoryLimit& limit);

// "7.4 GB", "120 MB": one decimal for sizes in messages.
std::string format_bytes(double bytes);

}  // namespace phongcl
