// phongcl serve while its render thread is busy for a long time (a scene whose meshes take seconds
// to read and build a BVH for): the page still answers within 1 s, and SIGTERM ends the process
// within 2 s with the exit status of a normal stop, without waiting for the render.
#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <future>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "opencl_required.h"
#include "peers/knot_mesh.h"
#include "serve_process.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// The default scene with every light casting shadows against `copies` instances of `mesh` beside
// its own objects: the next frame reads the mesh and builds a BVH of all its triangles.
json slow_scene(const std::filesystem::path& mesh, int copies) {
  json scene = json::parse(testing::read_text(PHONGCL_SOURCE_DIR "/scenes/default/scene.json"));
  for (json& light : scene["lights"]) light["shadows"] = true;
  for (int i = 0; i < copies; ++i)
    scene["objects"].push_back({{"type", "transform"},
                                {"translate", {0, 4 + i, 0}},
                                {"children", {{{"type", "mesh"}, {"file", mesh.string()}, {"material", 1}}}}});
  return scene;
}

// Polls /api/stats until `holds` is true of it; false after `limit`.
template <typename Condition>
bool stats_show(httplib::Client& client, Condition holds, std::chrono::milliseconds limit) {
  const auto deadline = Clock::now() + limit;
  while (Clock::now() < deadline) {
    const auto stats = client.Get("/api/stats");
    if (stats && stats->status == 200 && holds(json::parse(stats->body))) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

void put(httplib::Client& client, const char* path, const std::string& body) {
  const auto result = client.Put(path, body, "application/json");
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << path << ": " << result->body;
}

TEST(ServeStop, ALongRenderNeitherDelaysThePageNorHoldsSigterm) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  testing::TempDir dir;
  write_ply(dir / "dense.ply", trefoil_knot(20000, 50));  // 2 million triangles
  testing::ServeProcess serve("--scene scenes/default/scene.json --port 0");
  ASSERT_GT(serve.port(), 0) << serve.output();
  httplib::Client client("127.0.0.1", serve.port());
  // The first frame shaded and nobody shown it: the render thread shades nothing more until a
  // request waits, so both edits below go into one frame.
  ASSERT_TRUE(stats_show(client, [](const json& stats) { return stats["frames"] >= 1; }, std::chrono::seconds(60)));
  put(client, "/api/scene", slow_scene(dir / "dense.ply", 4).dump());
  put(client, "/api/settings", R"({"shadows": "geometry"})");
  auto slow_frame = std::async(std::launch::async, [port = serve.port()] {
    httplib::Client own("127.0.0.1", port);
    own.set_read_timeout(std::chrono::seconds(60));
    const auto image = own.Get("/api/image?format=jpeg");
    return image ? image->status : -1;
  });
  ASSERT_TRUE(stats_show(client, [](const json& stats) { return stats["waiting_for_frames"] >= 1; },
                         std::chrono::seconds(10)))
      << "no request ever waited for the slow frame";

  const auto asked = Clock::now();
  const auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_LT(Clock::now() - asked, std::chrono::seconds(1)) << "the page waited for the render";

  const std::optional<int> status = serve.stop_within(SIGTERM, std::chrono::seconds(2));
  ASSERT_TRUE(status) << "still running 2 s after SIGTERM: " << serve.output();
  EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0) << serve.output();
  EXPECT_NE(serve.output().find("phongcl serve: stopped"), std::string::npos) << serve.output();
  EXPECT_NE(slow_frame.get(), 200) << "the frame was shaded before SIGTERM: the render was too short to test";
}

}  // namespace
}  // namespace phongcl
