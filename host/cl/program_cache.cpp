#include "cl/program_cache.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "common/atomic_file.h"
#include "common/writable_directory.h"

namespace phongcl {

namespace fs = std::filesystem;

namespace {

// FNV-1a: stable across runs and platforms, unlike std::hash. Collisions are guarded by storing
// the whole key in the file and comparing it on load.
std::string fnv1a_hex(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  std::ostringstream hex;
  hex << std::hex << hash;
  return hex.str();
}

std::string cache_key(const DeviceInfo& device, const std::string& source, const std::string& options) {
  return device.platform + "\n" + device.platform_version + "\n" + device.name + "\n" + device.driver_version +
         "\n" + device.device_version + "\n" + options + "\n" + source;
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// File format: the key's length and text, then the device binary.
std::string read_cached_binary(const fs::path& file, const std::string& key) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return {};
  std::size_t key_length = 0;
  in >> key_length;
  in.get();
  std::string stored_key(key_length, '\0');
  in.read(stored_key.data(), static_cast<std::streamsize>(key_length));
  if (!in || stored_key != key) return {};
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

const char* to_string(CacheOutcome outcome) {
  switch (outcome) {
    case CacheOutcome::memory_hit: return "cache hit (memory)";
    case CacheOutcome::disk_hit: return "cache hit (disk)";
    case CacheOutcome::compiled: return "compiled";
  }
  return "?";
}

ProgramCache::ProgramCache(fs::path disk_directory, ProgramCacheLimits limits)
    : limits_(limits), disk_directory_(std::move(disk_directory)) {}

void ProgramCache::remember(const std::string& key, const cl::Program& program) {
  memory_.emplace_front(key, program);
  index_[key] = memory_.begin();
  while (memory_.size() > std::max<std::size_t>(limits_.memory_programs, 1)) {
    index_.erase(memory_.back().first);
    memory_.pop_back();  // kernels made from it keep it alive as long as they need it
  }
}

void ProgramCache::trim_disk() {
  struct Binary {
    fs::file_time_type used;
    std::uintmax_t bytes;
    fs::path file;
  };
  std::vector<Binary> binaries;
  std::uintmax_t total = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(disk_directory_, ec)) {
    if (entry.path().extension() != ".clbin") continue;
    std::error_code stat_error;
    const std::uintmax_t bytes = entry.file_size(stat_error);
    const fs::file_time_type used = entry.last_write_time(stat_error);
    if (stat_error) continue;  // removed by another process meanwhile
    binaries.push_back({used, bytes, entry.path()});
    total += bytes;
  }
  std::sort(binaries.begin(), binaries.end(), [](const Binary& a, const Binary& b) { return a.used < b.used; });
  for (std::size_t i = 0; i < binaries.size() && (binaries.size() - i > limits_.disk_files || total > limits_.disk_bytes); ++i) {
    std::error_code ignored;
    fs::remove(binaries[i].file, ignored);
    total -= binaries[i].bytes;
  }
}

fs::path ProgramCache::default_directory() {
  fs::path dir;
  if (const char* own = std::getenv("PHONGCL_CACHE_DIR"); own && *own) dir = own;
  else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) dir = fs::path(xdg) / "phongcl";
  else if (const char* home = std::getenv("HOME"); home && *home) dir = fs::path(home) / ".cache" / "phongcl";
  return !dir.empty() && ensure_writable_directory(dir) ? dir : fs::path();
}

BuiltProgram ProgramCache::build(const ComputeContext& compute, const std::string& source, const std::string& options) {
  const std::string key = cache_key(compute.device.info, source, options);
  if (const auto found = index_.find(key); found != index_.end()) {
    memory_.splice(memory_.begin(), memory_, found->second);  // now the most recently used
    return {found->second->second, CacheOutcome::memory_hit, 0.0};
  }
  const auto start = std::chrono::steady_clock::now();
  const fs::path file = disk_directory_.empty() ? fs::path() : disk_directory_ / (fnv1a_hex(key) + ".clbin");

  if (!file.empty()) {
    const std::string binary = read_cached_binary(file, key);
    if (!binary.empty()) {
      try {
        cl::Program program(compute.context, {compute.device.handle},
                            cl::Program::Binaries{std::vector<unsigned char>(binary.begin(), binary.end())});
        program.build({compute.device.handle}, options.c_str());
        remember(key, program);
        std::error_code ignored;
        fs::last_write_time(file, fs::file_time_type::clock::now(), ignored);  // used now: kept longest
        return {program, CacheOutcome::disk_hit, milliseconds_since(start)};
      } catch (const cl::Error&) {
        disk_problem_ = file.string() + ": stale or unusable cached binary, rebuilt from source";
      }
    }
  }

  cl::Program program(compute.context, source);
  program.build({compute.device.handle}, options.c_str());
  const double build_ms = milliseconds_since(start);
  remember(key, program);

  if (!file.empty()) {
    try {
      const auto binaries = program.getInfo<CL_PROGRAM_BINARIES>();
      fs::create_directories(disk_directory_);
      write_atomically(file, [&](const fs::path& temp) {
        std::ofstream out(temp, std::ios::binary);
        out << key.size() << '\n' << key;
        out.write(reinterpret_cast<const char*>(binaries.front().data()),
                  static_cast<std::streamsize>(binaries.front().size()));
        out.close();  // a failure in the final flush must not leave a truncated binary in the cache
        if (!out) throw std::runtime_error("write failed");
      });
      trim_disk();
    } catch (const std::exception& error) {
      disk_problem_ = "cannot write program cache " + file.string() + ": " + error.what();
    }
  }
  return {program, CacheOutcome::compiled, build_ms};
}

}  // namespace phongcl
