// libFuzzer harness: scene JSON as load_scene reads it. An InputError is the expected answer to
// a bad file; any other exception, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/error.h"
#include "scene/camera_space.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const phongcl::Scene scene = phongcl::parse_scene(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
    phongcl::to_camera_space(scene);  // what --space camera does next
  } catch (const phongcl::InputError&) {
  }
  return 0;
}
