// libFuzzer harness: a mesh file as read_mesh reads it, through the PLY check and Assimp. An
// InputError is the expected answer to a bad file; any other exception, a crash (Assimp's asserts
// abort), a hang (-timeout) or an allocation over -malloc_limit_mb is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/error.h"
#include "geometry/mesh_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // read_mesh takes a path (Assimp reads other formats' side files beside it): one file per process.
  static const struct ScratchFile {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("phongcl_fuzz_mesh_" + std::to_string(::getpid()) + ".ply");
    ~ScratchFile() { std::filesystem::remove(path); }
  } scratch;
  const std::filesystem::path& file = scratch.path;
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), size);
  try {
    phongcl::read_mesh(file);
  } catch (const phongcl::InputError&) {
  }
  return 0;
}
