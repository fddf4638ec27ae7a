// phongcl serve and the scene's objects: POST /api/save never writes over a mesh of the scene as
// it is held.
#include <gtest/gtest.h>
#include <httplib.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "peers/knot_mesh.h"
#include "serve_support.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using nlohmann::json;
using testing::RunningServer;
using testing::TempDir;

json default_scene() { return json::parse(testing::read_text(testing::kServeSceneFile)); }

void put(httplib::Client& client, const char* path, const json& body) {
  const auto result = client.Put(path, body.dump(), "application/json");
  ASSERT_TRUE(result);
  ASSERT_EQ(result->status, 200) << path << ": " << result->body;
}

// A PUT can name a mesh after start-up that --save names too: saving would replace it.
TEST(ServeObjects, SaveOverAMeshOfTheHeldSceneIsRefused) {
  if (!testing::have_opencl_device()) GTEST_SKIP() << "no OpenCL device on this machine";
  TempDir dir;
  write_ply(dir / "rock.ply", trefoil_knot(8, 4));
  const std::string mesh_bytes = testing::read_text(dir / "rock.ply");
  RunningServer server(dir / "rock.ply");
  auto client = server.client();
  json scene = default_scene();
  scene["objects"].push_back({{"type", "mesh"}, {"file", (dir / "rock.ply").string()}, {"material", 1}});
  put(client, "/api/scene", scene);
  const auto result = client.Post("/api/save", "", "application/json");
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 409) << result->body;
  EXPECT_NE(result->body.find("the scene's mesh '" + (dir / "rock.ply").string() + "'"), std::string::npos) << result->body;
  EXPECT_TRUE(testing::read_text(dir / "rock.ply") == mesh_bytes) << "the mesh was replaced";
}

}  // namespace
}  // namespace phongcl
