// phongcl serve: every HTTP endpoint of the real server on a loopback port, valid and invalid
// input, images checked against the scalar reference, and the binary's shutdown on SIGTERM.
#include <gtest/gtest.h>
#include <httplib.h>
#include <png.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <turbojpeg.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstring>
#include <fstream>
#include <future>
#include <limits>
#include <memory>
#include <thread>

#include <nlohmann/json.hpp>

#include "accuracy_bound.h"
#include "cl/device.h"
#include "cli_runner.h"
#include "gbuffer/layouts.h"
#include "opencl_required.h"
#include "reference/reference.h"
#include "color/color_conversion.h"
#include "color/display.h"
#include "serve/relight_server.h"
#include "shading/shadow_settings.h"
#include "serve_process.h"
#include "serve_support.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using nlohmann::json;
using testing::TempDir;

using testing::RunningServer;
using testing::ServeProcess;
const std::filesystem::path& kSceneFile = testing::kServeSceneFile;

std::string file_text(const std::filesystem::path& file) { return testing::read_text(file); }

class Serve : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!list_devices().empty()) server_ = new RunningServer();
  }
  static void TearDownTestSuite() {
    delete server_;
    server_ = nullptr;
  }
  void SetUp() override {
    PHONGCL_REQUIRE_OPENCL(server_ != nullptr);
    // Each test starts from the scene file and the default settings.
    auto client = server_->client();
    ASSERT_EQ(client.Put("/api/scene", file_text(kSceneFile), "application/json")->status, 200);
    ASSERT_EQ(client.Put("/api/settings", R"({"precision": "precise", "specialise": true, "shadows": "auto"})",
                         "application/json")->status, 200);
  }
  static RunningServer* server_;
};
RunningServer* Serve::server_ = nullptr;

json body_json(const httplib::Result& result) {
  EXPECT_TRUE(result) << "no response";
  if (!result) return {};
  EXPECT_EQ(result->get_header_value("Content-Type"), "application/json");
  return json::parse(result->body);
}

// A 4xx answered with {"error": "<one line>"} that contains `needle`.
void expect_error(const httplib::Result& result, int status, const std::string& needle) {
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, status) << result->body;
  const json body = body_json(result);
  ASSERT_TRUE(body.contains("error")) << result->body;
  const std::string message = body["error"];
  EXPECT_NE(message.find(needle), std::string::npos) << "message: " << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
}

json default_scene() { return json::parse(file_text(kSceneFile)); }

std::uint64_t frames_shaded(httplib::Client& client) { return body_json(client.Get("/api/stats"))["frames"]; }

// Polls the server's frame counter until it reaches `count`; the deadline only ends a hung server.
void wait_for_frames(httplib::Client& client, std::uint64_t count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  while (frames_shaded(client) < count) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the server never shaded frame " << count;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

// Polls the server until `count` requests wait for a frame, so that what follows happens while
// they wait; the deadline only ends a hung server.
void wait_for_waiting_requests(httplib::Client& client, std::size_t count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  while (body_json(client.Get("/api/stats"))["waiting_for_frames"].get<std::size_t>() < count) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "fewer than " << count << " requests ever waited";
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

Image decode_exr(const std::string& bytes) {
  TempDir dir("serve");
  std::ofstream(dir / "image.exr", std::ios::binary) << bytes;
  return read_exr(dir / "image.exr");
}

std::vector<std::uint8_t> decode_png(const std::string& bytes, int& width, int& height) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size())) throw std::runtime_error(png.message);
  png.format = PNG_FORMAT_RGBA;
  std::vector<std::uint8_t> rgba(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, rgba.data(), 0, nullptr)) throw std::runtime_error(png.message);
  width = static_cast<int>(png.width);
  height = static_cast<int>(png.height);
  return rgba;
}

// The kernel against the scalar reference of the same scene: the product's bound, on every covered
// pixel; an EXR is black where alpha is 0 (the reference leaves the scene's background colour there).
void expect_matches_reference(const Image& served, const Scene& scene, const GBuffer& gbuffer) {
  const Image expected = reference_image(scene, gbuffer);
  ASSERT_EQ(served.width, expected.width);
  ASSERT_EQ(served.height, expected.height);
  std::vector<bool> covered(expected.pixel_count());
  for (std::size_t i = 0; i < covered.size(); ++i) {
    covered[i] = expected.pixel(i)[3] > 0.0f;
    for (int c = 0; c < 4 && !covered[i]; ++c) ASSERT_EQ(served.pixel(i)[c], 0.0f) << "transparent pixel " << i << " channel " << c;
  }
  const ErrorStats error = testing::shading_error(served, expected, covered);
  EXPECT_LE(error.max_rel, testing::kRelativeBound) << "worst pixel (" << error.worst_x << ", " << error.worst_y
                                                    << "): served " << error.worst_test << ", reference "
                                                    << error.worst_expected;
  EXPECT_EQ(error.nonfinite_mismatches, 0u);
}

TEST_F(Serve, PageAndItsFilesAreServed) {
  auto client = server_->client();
  const auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(page->body.find("<html"), std::string::npos);
  for (const char* file : {"/app.js", "/style.css"}) {
    const auto result = client.Get(file);
    ASSERT_TRUE(result);
    EXPECT_EQ(result->status, 200) << file;
    EXPECT_NE(page->body.find(std::string(file).substr(1)), std::string::npos) << "the page loads " << file;
  }
}

TEST_F(Serve, UnknownPathsAnswerJson404) {
  auto client = server_->client();
  expect_error(client.Get("/api/nothing"), 404, "GET /api/nothing");
  expect_error(client.Delete("/api/scene"), 404, "DELETE /api/scene");
}

TEST_F(Serve, SceneRoundTripsAndEditsShadeLikeTheReference) {
  auto client = server_->client();
  const auto got = client.Get("/api/scene");
  EXPECT_EQ(body_json(got), default_scene());
  const int version = std::stoi(got->get_header_value("X-Scene-Version"));

  json edited = default_scene();
  edited["lights"][0]["color"] = {0.2, 0.9, 0.4};
  edited["lights"][0]["position"] = {-2.0, 3.0, 1.5};
  edited["materials"][0]["shininess"] = 7;
  const json put = body_json(client.Put("/api/scene", edited.dump(), "application/json"));
  EXPECT_EQ(put["scene_version"], version + 1);
  EXPECT_EQ(body_json(client.Get("/api/scene")), edited);

  const auto image = client.Get("/api/image?format=exr");
  ASSERT_TRUE(image);
  ASSERT_EQ(image->status, 200);
  EXPECT_EQ(image->get_header_value("X-Scene-Version"), std::to_string(version + 1));
  expect_matches_reference(decode_exr(image->body), parse_scene(edited.dump(), kSceneFile), server_->session().gbuffer());
}

// The material panel's principled inputs (web/app.js): a principled material's roughness and metallic
// edited live shade as the reference says.
TEST_F(Serve, APrincipledMaterialsRoughnessAndMetallicEditLive) {
  auto client = server_->client();
  json edited = default_scene();
  edited["materials"][0] = {{"specular_model", "principled"}, {"base_color", {0.8, 0.3, 0.2}}, {"roughness", 0.25}, {"metallic", 1}};
  for (double roughness : {0.25, 0.6}) {
    edited["materials"][0]["roughness"] = roughness;
    const auto put = client.Put("/api/scene", edited.dump(), "application/json");
    ASSERT_TRUE(put);
    ASSERT_EQ(put->status, 200) << put->body;
    const auto image = client.Get("/api/image?format=exr");
    ASSERT_TRUE(image);
    expect_matches_reference(decode_exr(image->body), parse_scene(edited.dump(), kSceneFile), server_->session().gbuffer());
  }
}

TEST_F(Serve, BadScenesAre400AndLeaveTheHeldSceneUnchanged) {
  auto client = server_->client();
  const std::string before = client.Get("/api/scene")->body;
  json unknown = default_scene();
  unknown["lights"][0]["falloff_typo"] = 1;
  json negative = default_scene();
  negative["lights"][1]["color"] = {1, -1, 1};
  json too_few_materials = default_scene();
  too_few_materials["materials"] = json::array({too_few_materials["materials"][0]});
  too_few_materials.erase("objects");
  json other_gbuffer = default_scene();
  other_gbuffer["gbuffer"] = "elsewhere.exr";
  const std::pair<std::string, std::string> cases[] = {
      {"{\"camera\": ", "invalid JSON"},
      {"", "invalid JSON"},
      {"[1, 2]", "object"},
      {unknown.dump(), "unknown key 'falloff_typo'"},
      {negative.dump(), "lights[1].color"},
      {too_few_materials.dump(), "material"},
      {other_gbuffer.dump(), "gbuffer: cannot change while serving"},
  };
  for (const auto& [body, needle] : cases) {
    SCOPED_TRACE(body.substr(0, 60));
    expect_error(client.Put("/api/scene", body, "application/json"), 400, needle);
    EXPECT_EQ(client.Get("/api/scene")->body, before);
  }
}

TEST_F(Serve, HugePayloadsAreRefused) {
  auto client = server_->client();
  const std::string before = client.Get("/api/scene")->body;
  const std::string huge(kMaxRequestBytes + 1, ' ');
  expect_error(client.Put("/api/scene", huge, "application/json"), 413, "too large");
  EXPECT_EQ(client.Get("/api/scene")->body, before);
}

TEST_F(Serve, ImagesInEveryFormatAndWidth) {
  auto client = server_->client();
  const Image exr = decode_exr(client.Get("/api/image?format=exr")->body);
  const auto png = client.Get("/api/image?format=png&exposure=0.5&view=aces");
  ASSERT_EQ(png->status, 200);
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  int width = 0, height = 0;
  const std::vector<std::uint8_t> rgba = decode_png(png->body, width, height);
  ASSERT_EQ(width, 640);
  ASSERT_EQ(height, 480);
  DisplaySettings display;
  display.view = "aces";
  display.exposure_stops = 0.5;
  display.background = load_scene(kSceneFile).background;
  EXPECT_EQ(rgba, DisplayTransform(ColorConfig::builtin(), display).encode(exr))
      << "the PNG is the EXR's display encoding, over the scene's background";
  EXPECT_EQ(decode_png(client.Get("/api/image?format=png&exposure=0.5&tonemap=aces")->body, width, height), rgba)
      << "tonemap is view's old name";

  const auto jpeg = client.Get("/api/image?format=jpeg&width=320");
  ASSERT_EQ(jpeg->status, 200);
  EXPECT_EQ(jpeg->get_header_value("Content-Type"), "image/jpeg");
  const std::unique_ptr<void, int (*)(tjhandle)> decoder(tjInitDecompress(), tjDestroy);
  int subsampling = 0, colorspace = 0;
  ASSERT_EQ(tjDecompressHeader3(decoder.get(), reinterpret_cast<const unsigned char*>(jpeg->body.data()),
                                jpeg->body.size(), &width, &height, &subsampling, &colorspace), 0);
  EXPECT_EQ(width, 320);
  EXPECT_EQ(height, 240);

  for (const char* term : {"ambient", "diffuse", "specular"}) {
    const auto result = client.Get(std::string("/api/image?format=exr&aov=") + term);
    ASSERT_EQ(result->status, 200) << term;
    EXPECT_EQ(decode_exr(result->body).width, 640);
  }
}

TEST_F(Serve, BadImageParametersAre400) {
  auto client = server_->client();
  const std::pair<std::string, std::string> cases[] = {
      {"format=gif", "unknown image format 'gif'"},
      {"width=0", "'width' must be in [1, 640]"},
      {"width=641", "'width' must be in [1, 640]"},
      {"width=12abc", "must be an integer"},
      {"exposure=nan", "finite number"},
      {"exposure=1e9", "'exposure' must be in"},
      {"tonemap=filmic", "has no view 'filmic' (views: reinhard, aces, clamp)"},
      {"view=Filmic", "has no view 'Filmic' (views: reinhard, aces, clamp)"},
      {"view=aces&tonemap=aces", "give one"},
      {"display=XYZ", "no display 'XYZ' (displays: sRGB)"},
      {"look=Punchy", "no look 'Punchy' (looks: none)"},
      {"aov=normal", "combined, ambient, diffuse, specular or group.<name>"},
      {"aov=group.a.b", "combined, ambient, diffuse, specular or group.<name>"},
      {"colour=red", "unknown parameter 'colour'"},
      {"width=100&width=200", "more than once"},
  };
  for (const auto& [query, needle] : cases) expect_error(client.Get("/api/image?" + query), 400, needle);
  expect_error(client.Get("/api/frame?after=-1"), 400, "'after' must be in");
}

TEST_F(Serve, ColorsAndThePickersConversions) {
  auto client = server_->client();
  const json colors = body_json(client.Get("/api/colors"));
  EXPECT_EQ(colors["working_space"], "Linear Rec.709 (sRGB)");
  EXPECT_EQ(colors["default_display"], "sRGB");
  ASSERT_EQ(colors["displays"].size(), 1u);
  EXPECT_EQ(colors["displays"][0]["views"], json::array({"reinhard", "aces", "clamp"}));
  EXPECT_EQ(colors["displays"][0]["picker_space"], "sRGB");
  EXPECT_EQ(colors["looks"], json::array());
  // The picker's #ff8040 (sRGB-encoded) as working-space values, and back.
  const json working = body_json(client.Get("/api/color?rgb=1,0.5019608,0.2509804&from=sRGB&to=scene_linear"));
  const double expected[] = {1.0, 0.2158605, 0.0512695};  // the sRGB decoding of 255, 128, 64
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(working["rgb"][c].get<double>(), expected[c], 1e-6) << c;
  const json back = body_json(client.Get("/api/color?rgb=1,0.2158605,0.0512695&from=scene_linear&to=sRGB"));
  EXPECT_NEAR(back["rgb"][1].get<double>(), 0.5019608, 1e-6);
  expect_error(client.Get("/api/color?rgb=1,2&from=sRGB&to=scene_linear"), 400, "three finite numbers");
  expect_error(client.Get("/api/color?rgb=1,2,nan&from=sRGB&to=scene_linear"), 400, "three finite numbers");
  // Finite in, not finite out: a 400 saying so, not a 200 of nulls.
  expect_error(client.Get("/api/color?rgb=1e308,1e308,1e308&from=sRGB&to=scene_linear"), 400, "no finite value");
  expect_error(client.Get("/api/color?rgb=1,2,3&from=sRGB"), 400, "are required");
  expect_error(client.Get("/api/color?rgb=1,2,3&from=P3&to=scene_linear"), 400, "'P3': no such colour space");
}

TEST_F(Serve, SceneColoursInTheirOwnSpaceAreConverted) {
  auto client = server_->client();
  json scene = json::parse(client.Get("/api/scene")->body);
  scene["color_space"] = "sRGB";
  ASSERT_EQ(client.Put("/api/scene", scene.dump(), "application/json")->status, 200);
  EXPECT_EQ(json::parse(client.Get("/api/scene")->body)["color_space"], "sRGB") << "the document is held as sent";
  const Image served = decode_exr(client.Get("/api/image?format=exr")->body);
  Scene converted = parse_scene(scene.dump(), kSceneFile);
  convert_scene_colors(converted, ColorConfig::builtin());
  expect_matches_reference(served, converted, server_->session().gbuffer());
  scene["color_space"] = "ACEScg";
  scene["lights"][0]["color"] = json::array({1, 0, 0});  // outside Rec.709: negative green and blue
  expect_error(client.Put("/api/scene", scene.dump(), "application/json"), 400, "outside its gamut");
}

TEST_F(Serve, LongPollWaitsForANewerFrameAndTimesOutWith204) {
  auto client = server_->client();
  const auto current = client.Get("/api/image?format=jpeg");
  const std::string version = current->get_header_value("X-Frame-Version");
  const auto idle = client.Get("/api/frame?format=jpeg&timeout_ms=200&after=" + version);
  ASSERT_TRUE(idle);
  EXPECT_EQ(idle->status, 204);

  // A second client (another tab) edits while the first one waits.
  auto poller = std::async(std::launch::async, [&] {
    auto own = server_->client();
    return own.Get("/api/frame?format=jpeg&timeout_ms=30000&after=" + version);
  });
  wait_for_waiting_requests(client, 1);
  json edited = default_scene();
  edited["lights"][0]["color"] = {1, 0, 0};
  const json put = body_json(client.Put("/api/scene", edited.dump(), "application/json"));
  const auto frame = poller.get();
  ASSERT_TRUE(frame);
  ASSERT_EQ(frame->status, 200);
  EXPECT_GT(std::stoull(frame->get_header_value("X-Frame-Version")), std::stoull(version));
  EXPECT_EQ(frame->get_header_value("X-Scene-Version"), put["scene_version"].dump());
}

TEST_F(Serve, EditsCoalesceAndTheLastOneIsShown) {
  auto client = server_->client();
  const std::uint64_t frames_before = frames_shaded(client);
  json scene = default_scene();
  constexpr int kEdits = 30;
  for (int i = 0; i < kEdits; ++i) {
    scene["lights"][0]["position"] = {-3.0 + 0.2 * i, 3.0, 2.0};
    ASSERT_EQ(client.Put("/api/scene", scene.dump(), "application/json")->status, 200);
  }
  const Image shown = decode_exr(client.Get("/api/image?format=exr")->body);
  const std::uint64_t frames_after = frames_shaded(client);
  EXPECT_LT(frames_after - frames_before, static_cast<std::uint64_t>(kEdits)) << "every edit was shaded: no coalescing";
  expect_matches_reference(shown, parse_scene(scene.dump(), kSceneFile), server_->session().gbuffer());
}

// Edits nobody fetches a frame of are not all shaded: one frame ahead at most, then the newest
// state when a request asks. The frame ahead is awaited on the counter before the next edits, so a
// render thread that shaded every edit would be shading the second while the others arrive, and
// would have shaded more than the two frames counted after the fetch. Reading /api/stats (as the
// wait does) is not fetching a frame.
TEST_F(Serve, ShadesOneFrameAheadOfWhatIsFetched) {
  auto client = server_->client();
  ASSERT_EQ(client.Get("/api/image?format=exr")->status, 200);  // every frame so far has been taken
  const std::uint64_t frames_before = frames_shaded(client);
  json scene = default_scene();
  const auto move_light_to = [&](double x) {
    scene["lights"][0]["position"] = {x, 3.0, 2.0};
    ASSERT_EQ(client.Put("/api/scene", scene.dump(), "application/json")->status, 200);
  };
  move_light_to(-2.0);
  wait_for_frames(client, frames_before + 1);  // the one frame ahead
  for (double x : {-1.5, -1.0, -0.5}) move_light_to(x);
  const Image shown = decode_exr(client.Get("/api/image?format=exr")->body);
  EXPECT_EQ(frames_shaded(client) - frames_before, 2u) << "the frame ahead, then the fetched one, and no other";
  expect_matches_reference(shown, parse_scene(scene.dump(), kSceneFile), server_->session().gbuffer());
}

// The render loop shades into the image of a frame nobody reads any more: every value of it is
// written again. A canvas of NaN gives exactly the image a new one does.
TEST(ServeFrames, ACanvasIsOverwrittenWhole) {
  PHONGCL_REQUIRE_OPENCL(!list_devices().empty());
  RelightSession session(read_gbuffer(PHONGCL_SOURCE_DIR "/scenes/default/gbuffer.exr"), "");
  const Scene scene = parse_scene(file_text(kSceneFile), kSceneFile);
  const Image fresh = session.shade(scene, RenderSettings{}).image;
  Image canvas = image_like(session.gbuffer());
  std::fill(canvas.rgba.begin(), canvas.rgba.end(), std::numeric_limits<float>::quiet_NaN());
  const float* storage = canvas.rgba.data();
  const Image reused = session.shade(scene, RenderSettings{}, std::move(canvas)).image;
  EXPECT_EQ(reused.rgba.data(), storage) << "the canvas was not shaded into";
  ASSERT_EQ(reused.rgba.size(), fresh.rgba.size());
  for (std::size_t i = 0; i < fresh.rgba.size(); ++i)
    ASSERT_EQ(std::bit_cast<std::uint32_t>(reused.rgba[i]), std::bit_cast<std::uint32_t>(fresh.rgba[i])) << "float " << i;
}

// Frames fetched one after another reuse each other's images: each is still its own scene's.
TEST_F(Serve, EachFetchedFrameIsItsOwnScene) {
  auto client = server_->client();
  json scene = default_scene();
  const json lights = scene["lights"];
  for (int i = 0; i < 4; ++i) {
    scene["lights"] = i % 2 == 0 ? lights : json::array();
    ASSERT_EQ(client.Put("/api/scene", scene.dump(), "application/json")->status, 200);
    const Image shown = decode_exr(client.Get("/api/image?format=exr")->body);
    expect_matches_reference(shown, parse_scene(scene.dump(), kSceneFile), server_->session().gbuffer());
  }
}

TEST_F(Serve, SettingsChangeThePrecisionAndRejectBadInput) {
  auto client = server_->client();
  const json put = body_json(client.Put("/api/settings", R"({"precision": "fast"})", "application/json"));
  EXPECT_EQ(put["precision"], "fast");
  client.Get("/api/image?format=jpeg");
  const json stats = body_json(client.Get("/api/stats"));
  EXPECT_EQ(stats["frame"]["precision"], "fast");
  EXPECT_NE(stats["frame"]["kernel"].get<std::string>().find("fast"), std::string::npos) << stats.dump();
  expect_error(client.Put("/api/settings", R"({"precision": "quad"})", "application/json"), 400, "precision");
  expect_error(client.Put("/api/settings", R"({"lanes": 4})", "application/json"), 400, "unknown key 'lanes'");
  expect_error(client.Put("/api/settings", R"({"specialise": 1})", "application/json"), 400, "true or false");
  expect_error(client.Put("/api/settings", "{", "application/json"), 400, "invalid JSON");
  EXPECT_EQ(body_json(client.Get("/api/settings"))["precision"], "fast");
}

TEST_F(Serve, ShadowsAreASettingAndRejectBadInput) {
  auto client = server_->client();
  json scene = default_scene();
  for (json& light : scene["lights"]) light["shadows"] = true;
  ASSERT_EQ(client.Put("/api/scene", scene.dump(), "application/json")->status, 200);
  auto kernel_for = [&](const char* settings) {
    EXPECT_EQ(client.Put("/api/settings", settings, "application/json")->status, 200) << settings;
    client.Get("/api/image?format=jpeg");
    return body_json(client.Get("/api/stats"))["frame"]["kernel"].get<std::string>();
  };
  EXPECT_NE(kernel_for(R"({"shadows": "geometry"})").find("geometry shadows"), std::string::npos);
  EXPECT_NE(kernel_for(R"({"shadows": "screen", "shadow_steps": 16, "shadow_thickness": "0.5"})").find("screen shadows"),
            std::string::npos);
  EXPECT_EQ(kernel_for(R"({"shadows": "off"})").find("shadows"), std::string::npos);
  const json settings = body_json(client.Get("/api/settings"));
  EXPECT_EQ(settings["shadows"], "off");
  EXPECT_EQ(settings["shadow_steps"], 16);
  EXPECT_EQ(settings["shadow_thickness"], "0.5");
  EXPECT_EQ(settings["shadow_rays"], ShadowSettings{}.rays);
  expect_error(client.Put("/api/settings", R"({"shadows": "soft"})", "application/json"), 400, "shadow mode");
  expect_error(client.Put("/api/settings", R"({"shadow_steps": 0})", "application/json"), 400, "steps");
  expect_error(client.Put("/api/settings", R"({"shadow_thickness": "-1"})", "application/json"), 400, "thickness");
  expect_error(client.Put("/api/settings", R"({"shadow_rays": 2000})", "application/json"), 400, "shadow rays");
  EXPECT_EQ(body_json(client.Get("/api/settings"))["shadows"], "off");
}

TEST_F(Serve, StatsDescribeTheKernelAndTheFrameTimes) {
  auto client = server_->client();
  client.Get("/api/image?format=jpeg");
  const json stats = body_json(client.Get("/api/stats"));
  EXPECT_EQ(stats["width"], 640);
  EXPECT_EQ(stats["height"], 480);
  EXPECT_EQ(stats["device"], "test device");
  EXPECT_GE(stats["frames"].get<int>(), 1);
  EXPECT_NE(stats["frame"]["kernel"].get<std::string>().find("precise, specialised: 2 point"), std::string::npos);
  const json timings = stats["frame"]["timings"];
  EXPECT_GT(timings["kernel_ms"].get<double>(), 0.0);
  EXPECT_GE(timings["shade_ms"].get<double>(), timings["kernel_ms"].get<double>()) << "the kernel is part of the frame";
  EXPECT_GT(stats["encode_ms"]["jpeg"].get<double>(), 0.0);
  expect_error(client.Get("/api/stats?verbose=1"), 400, "unknown parameter 'verbose'");
}

// The served frame as an EXR, `query` added to the image request's.
Image served_exr(httplib::Client& client, const std::string& query) {
  const auto result = client.Get("/api/image?format=exr" + query);
  EXPECT_EQ(result->status, 200) << query << ": " << result->body;
  return decode_exr(result->body);
}

// Light groups: listed in the stats, shown with aov=group.<name>, soloed and muted on the host (the
// other lights, or the muted group's, at colour 0): soloed, the image is the ambient plus the group's
// layer; muted, it is the reference of the scene without that group's light.
TEST_F(Serve, LightGroupsAreListedShownSoloedAndMuted) {
  auto client = server_->client();
  json scene = default_scene();
  scene["lights"][0]["group"] = "key";
  scene["lights"][2]["group"] = "fill";
  ASSERT_EQ(client.Put("/api/scene", scene.dump(), "application/json")->status, 200);
  EXPECT_EQ(body_json(client.Get("/api/stats"))["light_groups"], json({"key", "fill"}));
  const auto image_of = [&](const std::string& query) { return served_exr(client, query); };
  const Image key = image_of("&aov=group.key"), ambient = image_of("&aov=ambient");
  expect_error(client.Get("/api/image?format=exr&aov=group.rim"), 400, "no light group 'rim'");

  ASSERT_EQ(client.Put("/api/settings", R"({"solo": "key"})", "application/json")->status, 200);
  const Image soloed = image_of("");
  Image expected = ambient;
  for (std::size_t i = 0; i < expected.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) expected.pixel(i)[c] += key.pixel(i)[c];
  std::vector<bool> covered(expected.pixel_count());
  for (std::size_t i = 0; i < covered.size(); ++i) covered[i] = soloed.pixel(i)[3] > 0.0f;
  const ErrorStats solo_error = testing::shading_error(soloed, expected, covered);
  EXPECT_LE(solo_error.max_rel, 1e-5) << "worst pixel (" << solo_error.worst_x << ", " << solo_error.worst_y << ")";

  ASSERT_EQ(client.Put("/api/settings", R"({"solo": "", "mute": ["key"]})", "application/json")->status, 200);
  json without_key = scene;
  without_key["lights"][0]["color"] = {0, 0, 0};
  expect_matches_reference(image_of(""), parse_scene(without_key.dump(), kSceneFile), server_->session().gbuffer());
  const json settings = body_json(client.Get("/api/settings"));
  EXPECT_EQ(settings["solo"], "");
  EXPECT_EQ(settings["mute"], json({"key"}));
  expect_error(client.Put("/api/settings", R"({"solo": "a b"})", "application/json"), 400, "letters, digits");
  // As aov= refuses it: soloing a group the scene lacks would darken every light.
  expect_error(client.Put("/api/settings", R"({"solo": "rim"})", "application/json"), 400,
               "the scene has no light group 'rim' (groups: key, fill)");
  expect_error(client.Put("/api/settings", R"({"mute": "key"})", "application/json"), 400, "array");
}

// Area lights' groups are listed after the other lights', and solo and mute reach area lights too:
// muted, the image is the one of the scene without that area light.
TEST_F(Serve, AreaLightGroupsAreListedAndMuted) {
  auto client = server_->client();
  json scene = default_scene();
  scene["lights"][0]["group"] = "key";
  json panel = {{"type", "area"}, {"shape", "rect"}, {"position", {0, 4, 2}}, {"direction", {0, -1, -0.3}},
                {"up", {0, 0, 1}},  {"size", {2, 1}},    {"color", {3, 3, 3}},    {"group", "panel"}};
  scene["lights"].push_back(panel);
  ASSERT_EQ(client.Put("/api/scene", scene.dump(), "application/json")->status, 200);
  EXPECT_EQ(body_json(client.Get("/api/stats"))["light_groups"], json({"key", "panel"}));
  const auto image_of = [&](const std::string& query) { return served_exr(client, query); };
  const Image lit_by_panel = image_of("&aov=group.panel");
  bool any_lit = false;
  for (std::size_t i = 0; i < lit_by_panel.pixel_count(); ++i) any_lit |= lit_by_panel.pixel(i)[0] > 0.0f;
  EXPECT_TRUE(any_lit) << "the panel lights nothing: the test checks too little";
  ASSERT_EQ(client.Put("/api/settings", R"({"mute": ["panel"]})", "application/json")->status, 200);
  const Image muted = image_of("");
  ASSERT_EQ(client.Put("/api/settings", R"({"mute": []})", "application/json")->status, 200);
  scene["lights"].erase(scene["lights"].size() - 1);
  ASSERT_EQ(client.Put("/api/scene", scene.dump(), "application/json")->status, 200);
  const Image without = image_of("");
  std::vector<bool> covered(without.pixel_count());
  for (std::size_t i = 0; i < covered.size(); ++i) covered[i] = without.pixel(i)[3] > 0.0f;
  const ErrorStats error = testing::shading_error(muted, without, covered);
  EXPECT_LE(error.max_rel, 1e-5) << "worst pixel (" << error.worst_x << ", " << error.worst_y << ")";
}

TEST_F(Serve, PickReadsTheGBufferUnderTheCursor) {
  auto client = server_->client();
  const GBuffer& gbuffer = server_->session().gbuffer();
  const json pick = body_json(client.Get("/api/pick?x=320&y=240"));
  ASSERT_TRUE(pick["shaded"].get<bool>());
  const std::size_t i = 240 * 640 + 320;
  EXPECT_DOUBLE_EQ(pick["position"][1].get<double>(), gbuffer.position[1][i]);
  const glm::dvec3 normal{pick["normal"][0], pick["normal"][1], pick["normal"][2]};
  EXPECT_NEAR(glm::length(normal), 1.0, 1e-12);
  EXPECT_EQ(pick["material"].get<int>(), static_cast<int>(gbuffer.material[i]));
  // Some pixel of the default scene is background; find one and pick it.
  std::size_t background = 0;
  while (background < gbuffer.pixel_count() && gbuffer.material[background] >= 0) ++background;
  ASSERT_LT(background, gbuffer.pixel_count());
  const json none = body_json(client.Get("/api/pick?x=" + std::to_string(background % 640) + "&y=" +
                                         std::to_string(background / 640)));
  EXPECT_FALSE(none["shaded"].get<bool>());
  expect_error(client.Get("/api/pick?x=640&y=0"), 400, "'x' must be in [0, 639]");
  expect_error(client.Get("/api/pick?x=1"), 400, "required");
}

TEST_F(Serve, BeautyIs404WithoutOne) {
  auto client = server_->client();
  expect_error(client.Get("/api/beauty?format=png"), 404, "no beauty pass");
  EXPECT_EQ(body_json(client.Get("/api/stats"))["beauty"], false);
}

// A Blender render's Combined, as the G-buffer read it, in every format, at a width, and its
// parameters checked like the frame's.
TEST(ServeBeauty, ServesTheRenderersOwnImage) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const std::filesystem::path fixtures = PHONGCL_SOURCE_DIR "/tests/fixtures/blender";
  ReadOptions options;
  options.beauty = true;
  GBuffer gbuffer = read_gbuffer(fixtures / "cycles.exr", options).gbuffer;
  ASSERT_TRUE(gbuffer.has_beauty());
  const Planes3 beauty = gbuffer.beauty;
  RunningServer server(std::move(gbuffer), fixtures / "scene.json");
  auto client = server.client();
  EXPECT_EQ(body_json(client.Get("/api/stats"))["beauty"], true);

  const auto exr = client.Get("/api/beauty?format=exr");
  ASSERT_EQ(exr->status, 200) << exr->body;
  const Image image = decode_exr(exr->body);
  ASSERT_EQ(image.pixel_count(), beauty[0].size());
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    for (int c = 0; c < 3; ++c) ASSERT_EQ(image.pixel(i)[c], beauty[c][i]) << "pixel " << i << " channel " << c;
    ASSERT_EQ(image.pixel(i)[3], 1.0f) << "pixel " << i;
  }
  int width = 0, height = 0;
  const auto png = client.Get("/api/beauty?format=png&exposure=1&view=clamp");
  ASSERT_EQ(png->status, 200);
  DisplaySettings display;
  display.view = "clamp";
  display.exposure_stops = 1.0;
  EXPECT_EQ(decode_png(png->body, width, height), DisplayTransform(ColorConfig::builtin(), display).encode(image));
  const auto small = client.Get("/api/beauty?format=png&width=32");
  ASSERT_EQ(small->status, 200);
  decode_png(small->body, width, height);
  EXPECT_EQ(width, 32);
  EXPECT_EQ(height, 24);
  expect_error(client.Get("/api/beauty?aov=diffuse"), 400, "unknown parameter 'aov'");
  expect_error(client.Get("/api/beauty?format=gif"), 400, "unknown image format 'gif'");
  expect_error(client.Get("/api/beauty?width=65"), 400, "'width' must be in [1, 64]");
}

TEST_F(Serve, SaveWithoutAPathIs409) {
  auto client = server_->client();
  expect_error(client.Post("/api/save", "", "application/json"), 409, "--save");
}

TEST(ServeSave, WritesTheHeldSceneAtomically) {
  PHONGCL_REQUIRE_OPENCL(!list_devices().empty());
  TempDir dir("serve_save");
  RunningServer server(dir / "saved.json");
  auto client = server.client();
  json edited = default_scene();
  edited["lights"][1]["color"] = {0.25, 0.5, 0.75};
  ASSERT_EQ(client.Put("/api/scene", edited.dump(), "application/json")->status, 200);
  const json saved = body_json(client.Post("/api/save", "", "application/json"));
  EXPECT_EQ(saved["saved"], (dir / "saved.json").string());
  EXPECT_EQ(json::parse(file_text(dir / "saved.json")), edited);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path), {}), 1) << "no temporary file left";
  EXPECT_NO_THROW(load_scene(dir / "saved.json")) << "the saved file is a valid scene";
}

TEST(ServeShutdown, StopEndsWaitingRequestsPromptly) {
  PHONGCL_REQUIRE_OPENCL(!list_devices().empty());
  auto server = std::make_unique<RunningServer>();
  auto client = server->client();
  const std::string version = client.Get("/api/image?format=jpeg")->get_header_value("X-Frame-Version");
  auto poll = std::async(std::launch::async, [&] {
    auto own = server->client();
    return own.Get("/api/frame?timeout_ms=60000&after=" + version);
  });
  wait_for_waiting_requests(client, 1);
  const auto start = std::chrono::steady_clock::now();
  server.reset();
  poll.wait();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10)) << "the long poll held shutdown";
}

TEST(ServeCli, PrintsTheUrlAndStopsCleanlyOnSigtermAndSigint) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  for (int signal : {SIGTERM, SIGINT}) {
    ServeProcess serve("--scene scenes/default/scene.json --port 0");
    ASSERT_GT(serve.port(), 0) << serve.output();
    EXPECT_NE(serve.output().find("url        http://127.0.0.1:"), std::string::npos) << serve.output();
    EXPECT_EQ(serve.output().find("warning"), std::string::npos) << "no warning on loopback";
    httplib::Client client("127.0.0.1", serve.port());
    client.set_read_timeout(std::chrono::seconds(120));
    const auto image = client.Get("/api/image?format=png");
    ASSERT_TRUE(image);
    EXPECT_EQ(image->status, 200);
    const int status = serve.stop(signal);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal, not a clean exit";
    EXPECT_EQ(WEXITSTATUS(status), 0);
    EXPECT_NE(serve.output().find(signal == SIGTERM ? "SIGTERM, stopping" : "SIGINT, stopping"), std::string::npos)
        << serve.output();
    EXPECT_NE(serve.output().find("phongcl serve: stopped"), std::string::npos);
  }
}

// The beauty pass is named in the summary when the file has one, and absent otherwise.
TEST(ServeCli, NamesTheBeautyPassItServes) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  ServeProcess blender("--scene tests/fixtures/blender/scene.json --gbuffer tests/fixtures/blender/cycles.exr --port 0");
  ASSERT_GT(blender.port(), 0) << blender.output();
  EXPECT_NE(blender.output().find("  beauty     Combined (GET /api/beauty"), std::string::npos) << blender.output();
  EXPECT_EQ(blender.stop(SIGTERM), 0);
  ServeProcess plain("--scene scenes/default/scene.json --port 0");
  ASSERT_GT(plain.port(), 0) << plain.output();
  EXPECT_EQ(plain.output().find("beauty"), std::string::npos) << plain.output();
  EXPECT_EQ(plain.stop(SIGTERM), 0);
}

TEST(ServeCli, WarnsWhenListeningBeyondLoopback) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  ServeProcess serve("--scene scenes/default/scene.json --host 0.0.0.0 --port 0");
  EXPECT_NE(serve.output().find("warning    listening on 0.0.0.0: anyone"), std::string::npos) << serve.output();
  EXPECT_GT(serve.port(), 0) << serve.output();
  const int status = serve.stop(SIGTERM);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST(ServeCli, RefusesABusyPortAndBadOptions) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  // A plain listening socket (httplib's own would share the port through SO_REUSEPORT).
  const int blocker = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(blocker, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(listen(blocker, 1), 0);
  socklen_t length = sizeof address;
  getsockname(blocker, reinterpret_cast<sockaddr*>(&address), &length);
  const int port = ntohs(address.sin_port);
  const testing::CliRun busy = testing::run_phongcl("serve --scene scenes/default/scene.json --port " + std::to_string(port));
  EXPECT_EQ(busy.exit_code, 1);
  EXPECT_NE(busy.err.find("cannot listen on 127.0.0.1:" + std::to_string(port)), std::string::npos) << busy.err;
  EXPECT_EQ(testing::run_phongcl("serve --scene scenes/default/scene.json --port 70000").exit_code, 2);
  const testing::CliRun camera = testing::run_phongcl("serve --scene scenes/default/scene.json --space camera");
  EXPECT_EQ(camera.exit_code, 1);
  EXPECT_NE(camera.err.find("--space camera is not supported"), std::string::npos) << camera.err;
  close(blocker);
}

}  // namespace
}  // namespace phongcl
