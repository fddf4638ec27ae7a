// libFuzzer harness: a G-buffer EXR as `phongcl shade` reads it, any layout, with positions
// rebuilt from depth where the file has depth but no position, then the material check.
// An InputError is the expected answer to a bad file; anything else is a finding.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.h"
#include "gbuffer/gbuffer.h"
#include "gbuffer/layouts.h"
#include "raycast/depth_reconstruction.h"
#include "scene/scene.h"

namespace {

// The reader takes a path: each input goes to one in-memory file, reached as /proc/self/fd/N.
const std::string& input_path() {
  static const std::string path = "/proc/self/fd/" + std::to_string(::memfd_create("fuzz.exr", 0));
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const int fd = std::stoi(input_path().substr(std::string("/proc/self/fd/").size()));
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, data, size, 0) != static_cast<ssize_t>(size)) return 0;
  phongcl::ReadOptions options;
  // 4 Mpixels: 16 planes of floats stay at 256 MB, well under the fuzzer's -malloc_limit_mb, so a
  // larger allocation is a finding (a size not checked against the limit), not a big window.
  options.max_pixels = std::uint64_t{1} << 22;
  try {
    phongcl::GBufferRead read = phongcl::read_gbuffer(input_path(), options);
    if (read.needs_positions_from_depth()) {
      phongcl::Camera camera;  // the user's camera matches the image, or the CLI says it does not
      camera.width = read.gbuffer.display_window.width();
      camera.height = read.gbuffer.display_window.height();
      for (const auto convention : {phongcl::DepthConvention::distance, phongcl::DepthConvention::view_z}) {
        read.depth_convention = convention;
        phongcl::positions_from_depth(read, camera);  // the second run finds the edges repaired
      }
    }
    phongcl::check_materials(read.gbuffer, 4);
  } catch (const phongcl::InputError&) {
  }
  return 0;
}
