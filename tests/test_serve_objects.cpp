// phongcl serve and the scene's objects: an edit of the objects (the shadows' geometry, the mesh
// files they name) shows in the next frame, a mesh that cannot be read fails the PUT or the next
// frame, and POST /api/save never writes over a mesh of the scene as it is held.
#include <gtest/gtest.h>
#include <httplib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "opencl_required.h"
#include "peers/knot_mesh.h"
#include "serve_support.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using nlohmann::json;
using testing::RunningServer;
using testing::TempDir;

json default_scene() { return json::parse(testing::read_text(testing::kServeSceneFile)); }

// The default scene with every light casting shadows (traced against the objects: "auto").
json shadowed_scene() {
  json scene = default_scene();
  for (json& light : scene["lights"]) light["shadows"] = true;
  return scene;
}

using testing::put_json;
using testing::served_exr;

double luminance(const Image& image, std::size_t pixel) {
  const float* rgba = image.pixel(pixel);
  return rgba[0] + rgba[1] + rgba[2];
}

// Pixels at least 5% darker in `shadowed` than in `lit`.
std::vector<std::size_t> darkened(const Image& lit, const Image& shadowed) {
  std::vector<std::size_t> pixels;
  for (std::size_t i = 0; i < lit.pixel_count(); ++i)
    if (luminance(shadowed, i) < 0.95 * luminance(lit, i)) pixels.push_back(i);
  return pixels;
}

// The spheres shadow the floor; without them (the floor alone, which shadows nothing the lights
// above it reach) the next frame is the unshadowed one.
TEST(ServeObjects, RemovingTheShadowingObjectsLightsWhatTheyShadowed) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  RunningServer server;
  auto client = server.client();
  const json scene = shadowed_scene();
  put_json(client, "/api/scene", scene);
  put_json(client, "/api/settings", {{"shadows", "off"}});
  const Image lit = served_exr(client);
  put_json(client, "/api/settings", {{"shadows", "auto"}});
  const Image shadowed = served_exr(client);
  const std::vector<std::size_t> in_shadow = darkened(lit, shadowed);
  ASSERT_GT(in_shadow.size(), 1000u) << "the spheres should shadow the floor";

  json floor_only = scene;
  floor_only["objects"] = json::array({scene["objects"][0]});
  put_json(client, "/api/scene", floor_only);
  const Image after = served_exr(client);
  std::size_t still_dark = 0;
  for (std::size_t i : in_shadow) still_dark += luminance(after, i) < 0.99 * luminance(lit, i);
  EXPECT_EQ(still_dark, 0u) << "of " << in_shadow.size() << " pixels the spheres shadowed";
}

// A mesh added by a PUT casts its shadow in the next frame, and a mesh file rewritten in place is
// read again for the next frame.
TEST(ServeObjects, AMeshAddedByAPutIsReadForTheNextFrame) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  TempDir dir;
  write_ply(dir / "knot.ply", trefoil_knot(48, 10));
  RunningServer server;
  auto client = server.client();
  json scene = shadowed_scene();
  put_json(client, "/api/scene", scene);
  const Image before = served_exr(client);

  scene["objects"].push_back({{"type", "transform"},
                              {"translate", {0, 3, 0}},
                              {"children", {{{"type", "mesh"}, {"file", (dir / "knot.ply").string()}, {"material", 1}}}}});
  put_json(client, "/api/scene", scene);
  EXPECT_GT(darkened(before, served_exr(client)).size(), 1000u) << "the knot above the scene should shadow it";

  TriangleMesh far_away;  // one small triangle beyond every light
  far_away.vertices = {{1000, 0, 0}, {1001, 0, 0}, {1000, 1, 0}};
  far_away.triangles = {{0, 1, 2}};
  write_ply(dir / "knot.ply", far_away);
  put_json(client, "/api/scene", scene);
  EXPECT_EQ(darkened(before, served_exr(client)).size(), 0u) << "the knot's file was rewritten: it shadows nothing";
}

// A mesh file that cannot be opened is a 400 naming it, the held scene unchanged; one that opens
// but is malformed fails the next frame, whose error names it.
TEST(ServeObjects, MeshesThatCannotBeReadFailThePutOrTheNextFrame) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  TempDir dir;
  RunningServer server;
  auto client = server.client();
  json scene = shadowed_scene();
  put_json(client, "/api/scene", scene);

  json missing = scene;
  missing["objects"].push_back({{"type", "mesh"}, {"file", (dir / "missing.ply").string()}, {"material", 1}});
  const auto refused = client.Put("/api/scene", missing.dump(), "application/json");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 400) << refused->body;
  EXPECT_NE(refused->body.find("missing.ply"), std::string::npos) << refused->body;
  EXPECT_EQ(json::parse(client.Get("/api/scene")->body), scene) << "the held scene is unchanged";

  std::ofstream(dir / "garbage.ply") << "ply\nformat binary_little_endian 1.0\nelement vertex 99999999\nproperty float x\nend_header\nxx";
  json garbage = scene;
  garbage["objects"].push_back({{"type", "mesh"}, {"file", (dir / "garbage.ply").string()}, {"material", 1}});
  put_json(client, "/api/scene", garbage);
  const auto frame = client.Get("/api/image?format=jpeg");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 422) << frame->body;
  EXPECT_NE(frame->body.find("garbage.ply"), std::string::npos) << frame->body;
}

// A PUT can name a mesh after start-up that --save names too: saving would replace it.
TEST(ServeObjects, SaveOverAMeshOfTheHeldSceneIsRefused) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  TempDir dir;
  write_ply(dir / "rock.ply", trefoil_knot(8, 4));
  const std::string mesh_bytes = testing::read_text(dir / "rock.ply");
  RunningServer server(dir / "rock.ply");
  auto client = server.client();
  json scene = default_scene();
  scene["objects"].push_back({{"type", "mesh"}, {"file", (dir / "rock.ply").string()}, {"material", 1}});
  put_json(client, "/api/scene", scene);
  const auto result = client.Post("/api/save", "", "application/json");
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 409) << result->body;
  EXPECT_NE(result->body.find("the scene's mesh '" + (dir / "rock.ply").string() + "'"), std::string::npos) << result->body;
  EXPECT_TRUE(testing::read_text(dir / "rock.ply") == mesh_bytes) << "the mesh was replaced";
}

}  // namespace
}  // namespace phongcl
