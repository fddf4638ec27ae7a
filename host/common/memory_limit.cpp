#include "common/memory_limit.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace phongcl {
namespace {

// A /proc file's "Name: N kB" line, in bytes; 0 when absent.
std::uint64_t proc_kilobytes(const char* file, const std::string& name) {
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (line.starts_with(name + ":")) return std::stoull(line.substr(name.size() + 1)) * 1024;
  return 0;
}

}  // namespace

MemoryLimit memory_limit() {
  MemoryLimit limit{std::numeric_limits<std::uint64_t>::max(), "no limit known"};
  if (const std::uint64_t available = proc_kilobytes("/proc/meminfo", "MemAvailable"))
    limit = {available, "the machine's available memory"};
  rlimit address_space{};
  if (::getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY) {
    const std::uint64_t mapped = proc_kilobytes("/proc/self/status", "VmSize");
    const std::uint64_t left = address_space.rlim_cur > mapped ? address_space.rlim_cur - mapped : 0;
    if (left < limit.bytes) limit = {left, "what the address-space limit (ulimit -v) leaves"};
  }
  return limit;
}

std::string format_bytes(double bytes) {
  char text[32];
  if (bytes >= 1e9) std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  else std::snprintf(text, sizeof text, "%.0f MB", std::max(1.0, bytes / 1e6));
  return text;
}

void check_memory(const std::string& task, const std::vector<MemoryNeed>& needs, const MemoryLimit& limit) {
  double total = 0;
  for (const MemoryNeed& need : needs) total += need.bytes;
  if (needs.empty() || total <= static_cast<double>(limit.bytes)) return;
  const MemoryNeed& largest =
      *std::max_element(needs.begin(), needs.end(), [](const auto& a, const auto& b) { return a.bytes < b.bytes; });
  throw std::runtime_error(task + " needs about " + format_bytes(total) + ", " + format_bytes(largest.bytes) +
                           " of it for " + largest.what + ": more than the " +
                           format_bytes(static_cast<double>(limit.bytes)) + " of " + limit.source);
}

}  // namespace phongcl
