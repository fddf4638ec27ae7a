// phongcl's estimate of a frame's memory (shading/frame_memory.h), through the real binary under a
// real address-space limit: a scene too large is one line naming what takes the memory, before
// the allocations, rather than std::bad_alloc half-way through.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "cli_runner.h"
#include "opencl_required.h"
#include "peers/knot_mesh.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using testing::TempDir;

bool under_address_sanitizer() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#endif
#endif
  return false;
}

// The default scene's G-buffer and camera, one light casting shadows and `instances` of one mesh.
std::string mesh_scene(int instances) {
  std::string objects;
  for (int i = 0; i < instances; ++i) objects += std::string(i ? ", " : "") + R"({"type": "mesh", "file": "rock.ply"})";
  return R"({"camera": {"eye": [0, 2, 8], "look_at": [0, 0.7, 0], "up": [0, 1, 0], "fov_y_deg": 40, "width": 640, "height": 480},
             "materials": [{}, {}, {}, {}, {}],
             "lights": [{"type": "point", "position": [0, 10, 0], "shadows": true}],
             "gbuffer": ")" PHONGCL_SOURCE_DIR R"(/scenes/default/gbuffer.exr",
             "objects": [)" + objects + "]}";
}

// A 500,000-triangle mesh listed twenty times under a 3 GB address-space limit: 10 million
// triangles of shadow geometry. It ended in a bare std::bad_alloc; one instance still shades.
TEST(CliMemory, ShadowGeometryBeyondTheLimitIsRefusedNamingIt) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  if (under_address_sanitizer()) GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: ulimit -v cannot hold it";
  TempDir dir;
  write_ply(dir / "rock.ply", trefoil_knot(1000, 250));
  std::ofstream(dir / "many.json") << mesh_scene(20);
  std::ofstream(dir / "one.json") << mesh_scene(1);
  const std::string limit = "ulimit -v 3000000; ";

  const testing::CliRun many = testing::run_phongcl(
      "shade --scene '" + (dir / "many.json").string() + "' --out '" + (dir / "many.exr").string() + "'", limit);
  EXPECT_EQ(many.exit_code, 1) << many.err;
  EXPECT_NE(many.err.find("shading this frame needs about"), std::string::npos) << many.err;
  EXPECT_NE(many.err.find("for the shadow geometry (10000000 triangles, meshes counted per instance: 20)"),
            std::string::npos)
      << many.err;
  EXPECT_NE(many.err.find("address-space limit (ulimit -v)"), std::string::npos) << many.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "many.exr"));

  const testing::CliRun one = testing::run_phongcl(
      "shade --scene '" + (dir / "one.json").string() + "' --out '" + (dir / "one.exr").string() + "'", limit);
  EXPECT_EQ(one.exit_code, 0) << one.err;
}

}  // namespace
}  // namespace phongcl
