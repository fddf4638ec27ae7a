// Cameras from a G-buffer's header: OpenEXR's worldToCamera and worldToNDC read into the scene's
// camera, and `shade` with a scene that has none, or one that disagrees.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "common/error.h"
#include "gbuffer/file_camera.h"
#include "image/image.h"
#include "raycast/raycast.h"
#include "scene/scene.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;
using testing::run_phongcl;

using testing::TempDir;

// OpenEXR's worldToCamera and worldToNDC for a phongcl camera, built here from their definitions
// (ImfStandardAttributes.h): camera space left-handed, x right, y up, z forward; NDC (0, 0) at the
// display window's upper left, (1, 1) at its lower right; row vectors, p' = p * M.
struct HeaderCamera {
  Imath::M44f world_to_camera, world_to_ndc;
};

HeaderCamera header_camera(const Camera& c, double shift_x = 0.0) {
  const glm::dvec3 f = glm::normalize(c.look_at - c.eye), r = glm::normalize(glm::cross(f, c.up)), u = glm::cross(r, f);
  const Imath::M44d camera_to_world(r.x, r.y, r.z, 0, u.x, u.y, u.z, 0, f.x, f.y, f.z, 0, c.eye.x, c.eye.y, c.eye.z, 1);
  const double tan_y = std::tan(glm::radians(c.fov_y_deg) / 2), tan_x = tan_y * c.width / c.height;
  // (x, y, z, 1) -> (x / (2 tan_x) + (0.5 + shift_x) z, -y / (2 tan_y) + 0.5 z, z, z), then / w = z.
  const Imath::M44d camera_to_ndc(1 / (2 * tan_x), 0, 0, 0, 0, -1 / (2 * tan_y), 0, 0, 0.5 + shift_x, 0.5, 1, 1, 0, 0, 0, 0);
  const Imath::M44d world_to_camera = camera_to_world.inverse();
  return {Imath::M44f(world_to_camera), Imath::M44f(world_to_camera * camera_to_ndc)};
}

// A native G-buffer with the header attributes, written through OpenEXR's API.
void write_with_camera(const GBuffer& g, const fs::path& file, const HeaderCamera* camera) {
  Imf::Header header(g.width, g.height);
  if (camera) {
    Imf::addWorldToCamera(header, camera->world_to_camera);
    Imf::addWorldToNDC(header, camera->world_to_ndc);
  }
  Imf::FrameBuffer frame;
  const auto add = [&](const char* name, const Plane& plane) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    frame.insert(name, Imf::Slice(Imf::FLOAT, (char*)plane.data(), sizeof(float), sizeof(float) * g.width));
  };
  add("P.X", g.position[0]), add("P.Y", g.position[1]), add("P.Z", g.position[2]);
  add("N.X", g.normal[0]), add("N.Y", g.normal[1]), add("N.Z", g.normal[2]);
  add("material", g.material);
  Imf::OutputFile out(file.c_str(), header);
  out.setFrameBuffer(frame);
  out.writePixels(g.height);
}

// The default scene at 64x48, and its JSON with the camera (and the gbuffer entry) taken out.
struct CameraFixture {
  Scene scene;
  GBuffer gbuffer;
  nlohmann::json without_camera;
};

CameraFixture camera_fixture() {
  std::ifstream in(fs::path(PHONGCL_SOURCE_DIR) / "scenes/default/scene.json");
  nlohmann::json json = nlohmann::json::parse(in);
  json["camera"]["width"] = 64;
  json["camera"]["height"] = 48;
  json.erase("gbuffer");
  CameraFixture f;
  f.scene = parse_scene(json.dump(), "scene.json");
  f.gbuffer = generate_gbuffer(f.scene);
  json.erase("camera");
  f.without_camera = json;
  return f;
}

void write_json(const nlohmann::json& json, const fs::path& file) { std::ofstream(file) << json.dump(2); }

TEST(FileCameras, WorldToCameraAndWorldToNdcGiveTheCamera) {
  TempDir dir;
  const CameraFixture f = camera_fixture();
  const HeaderCamera header = header_camera(f.scene.camera);
  write_with_camera(f.gbuffer, dir / "g.exr", &header);
  const auto camera = read_file_camera(dir / "g.exr");
  ASSERT_TRUE(camera.has_value());
  const Camera& c = f.scene.camera;
  const glm::dvec3 forward = glm::normalize(c.look_at - c.eye);
  for (int a = 0; a < 3; ++a) {
    // M44f: about 1e-7 relative of the eye's distance, amplified a little by the inverse.
    EXPECT_NEAR(camera->eye[a], c.eye[a], 1e-5 * glm::length(c.eye)) << "axis " << a;
    EXPECT_NEAR(camera->forward[a], forward[a], 1e-6) << "axis " << a;
  }
  const glm::dvec3 up(camera->up[0], camera->up[1], camera->up[2]);
  EXPECT_NEAR(glm::dot(up, forward), 0.0, 1e-6);
  EXPECT_GT(glm::dot(up, c.up), 0.9);
  EXPECT_NEAR(camera->fov_y_deg, c.fov_y_deg, 1e-4);
  EXPECT_EQ(camera->width, 64);
  EXPECT_EQ(camera->height, 48);

  write_with_camera(f.gbuffer, dir / "none.exr", nullptr);
  EXPECT_FALSE(read_file_camera(dir / "none.exr").has_value());
  const HeaderCamera shifted = header_camera(f.scene.camera, 0.1);
  write_with_camera(f.gbuffer, dir / "shift.exr", &shifted);
  EXPECT_THROW(read_file_camera(dir / "shift.exr"), InputError);
}

TEST(FileCameras, SceneWithoutCameraShadesWithTheFilesAndDisagreementIsWarned) {
  TempDir dir;
  const CameraFixture f = camera_fixture();
  const HeaderCamera header = header_camera(f.scene.camera);
  write_with_camera(f.gbuffer, dir / "g.exr", &header);
  write_json(f.without_camera, dir / "no_camera.json");
  const auto shade = [&](const fs::path& scene, const fs::path& gbuffer, const fs::path& out) {
    return run_phongcl("shade --scene " + scene.string() + " --gbuffer " + gbuffer.string() + " --out " + out.string());
  };
  const auto from_file = shade(dir / "no_camera.json", dir / "g.exr", dir / "a.exr");
  ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
  EXPECT_NE(from_file.out.find("camera from the file's worldToCamera and worldToNDC"), std::string::npos) << from_file.out;

  nlohmann::json with_camera = f.without_camera;
  const Camera& c = f.scene.camera;
  with_camera["camera"] = {{"eye", {c.eye.x, c.eye.y, c.eye.z}}, {"look_at", {c.look_at.x, c.look_at.y, c.look_at.z}},
                           {"up", {c.up.x, c.up.y, c.up.z}}, {"fov_y_deg", c.fov_y_deg}, {"width", 64}, {"height", 48}};
  write_json(with_camera, dir / "same.json");
  const auto same = shade(dir / "same.json", dir / "g.exr", dir / "b.exr");
  ASSERT_EQ(same.exit_code, 0) << same.err;
  EXPECT_EQ(same.out.find("disagree"), std::string::npos) << same.out;
  // The file's camera shades like the scene's (its eye is float-rounded: 1e-6 of its distance).
  const Image a = read_exr(dir / "a.exr"), b = read_exr(dir / "b.exr");
  for (std::size_t i = 0; i < a.pixel_count(); ++i)
    for (int ch = 0; ch < 4; ++ch) ASSERT_NEAR(a.pixel(i)[ch], b.pixel(i)[ch], 1e-4) << "pixel " << i;

  with_camera["camera"]["eye"] = {c.eye.x + 0.5, c.eye.y, c.eye.z};
  write_json(with_camera, dir / "moved.json");
  const auto moved = shade(dir / "moved.json", dir / "g.exr", dir / "c.exr");
  ASSERT_EQ(moved.exit_code, 0) << moved.err;
  EXPECT_NE(moved.out.find("warning    the scene's camera and the file's (worldToCamera, worldToNDC) disagree: eyes 0.5"),
            std::string::npos) << moved.out;

  write_with_camera(f.gbuffer, dir / "none.exr", nullptr);
  const auto neither = shade(dir / "no_camera.json", dir / "none.exr", dir / "d.exr");
  EXPECT_NE(neither.exit_code, 0);
  EXPECT_NE(neither.err.find("no \"camera\", and the G-buffer's header states none"), std::string::npos) << neither.err;
  EXPECT_FALSE(fs::exists(dir / "d.exr"));
}

}  // namespace
}  // namespace phongcl
