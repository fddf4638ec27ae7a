// phongcl serve over a render (serve --over): every frame is the render with the groups the page
// changed, the same composite `shade --over` makes; solo and mute take groups' passes out exactly;
// a scene that cannot be composited is refused at the PUT. The render is phongcl's own, written with
// a pass per light group as Blender writes one.
#include <gtest/gtest.h>
#include <httplib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "composite/relight_over.h"
#include "opencl_required.h"
#include "serve_support.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const fs::path kGBufferFile = PHONGCL_SOURCE_DIR "/scenes/default/gbuffer.exr";

// The default scene with its lights in groups key, fill and rim, as rendered.
json grouped_scene() {
  json scene = json::parse(testing::read_text(testing::kServeSceneFile));
  const char* groups[] = {"key", "fill", "rim"};
  for (std::size_t i = 0; i < scene["lights"].size(); ++i) scene["lights"][i]["group"] = groups[i % 3];
  scene["rendered"] = {{"lights", scene["lights"]}};
  return scene;
}

struct Render {
  Image combined;
  std::map<std::string, Image> passes;
};

// phongcl's shading of `scene_file` written as a render with light-group passes.
Render write_render(const fs::path& scene_file, const fs::path& file) {
  RelighterOptions options;
  options.terms = true;
  Relighter relighter(load_scene(scene_file), read_gbuffer(kGBufferFile), options);
  TermImages terms;
  Render render{relighter.shade(terms), {}};
  std::vector<ExrLayer> layers = {{"ViewLayer.Combined", &render.combined, true}};
  for (std::size_t g = 0; g < terms.groups.size(); ++g) {
    render.passes[terms.group_names[g]] = std::move(terms.groups[g]);
    layers.push_back({"ViewLayer.Combined_" + terms.group_names[g], &render.passes[terms.group_names[g]], false});
  }
  ExrWriteOptions keep;
  keep.keep_color_where_transparent = true;
  write_layered_exr(layers, file, keep);
  return render;
}

using testing::put_json;
using testing::served_exr;

// The largest difference over the pixels the render covers (the EXR the server sends has RGB 0 where
// alpha is 0), relative to max(1, |expected|).
float worst_covered_difference(const Image& served, const Image& expected) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < expected.pixel_count(); ++i) {
    if (expected.pixel(i)[3] == 0.0f) continue;
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, std::abs(served.pixel(i)[c] - expected.pixel(i)[c]) /
                                  std::max(1.0f, std::abs(expected.pixel(i)[c])));
  }
  return worst;
}

json over_groups(httplib::Client& client) {
  const auto stats = client.Get("/api/stats");
  EXPECT_TRUE(stats && stats->status == 200);
  return stats ? json::parse(stats->body)["over"] : json();
}

TEST(ServeOver, FramesAreTheRenderWithTheChangedGroupsComposited) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  testing::TempDir dir("serve_over");
  const json scene = grouped_scene();
  std::ofstream(dir / "scene.json") << scene.dump(1);
  const Render render = write_render(dir / "scene.json", dir / "render.exr");
  testing::RunningServer server(read_gbuffer(kGBufferFile), dir / "scene.json", {}, {}, dir / "render.exr");
  httplib::Client client = server.client();

  EXPECT_EQ(worst_covered_difference(served_exr(client), render.combined), 0.0f) << "no edit: the render";
  json over = over_groups(client);
  EXPECT_EQ(over["view_layer"], "ViewLayer");
  EXPECT_EQ(over["passes"], json::array({"fill", "key", "rim"}));
  for (const json& group : over["groups"]) EXPECT_EQ(group["change"], "unchanged") << group.dump();

  // The key moved: the frame is the composite that `shade --over` makes of the same scene.
  json moved = scene;
  moved["lights"][0]["position"][0] = moved["lights"][0]["position"][0].get<double>() + 0.5;
  put_json(client, "/api/scene", moved);
  std::ofstream(dir / "moved.json") << moved.dump(1);
  RelighterOptions options;
  options.terms = true;
  Relighter relighter(load_scene(dir / "scene.json"), read_gbuffer(kGBufferFile), options);
  const Image expected = relight_over(relighter, dir / "render.exr", load_scene(dir / "moved.json")).image;
  EXPECT_LT(worst_covered_difference(served_exr(client), expected), 1e-5f);
  over = over_groups(client);
  ASSERT_EQ(over["groups"].size(), 3u);
  EXPECT_EQ(over["groups"][0]["name"], "key");
  EXPECT_EQ(over["groups"][0]["change"], "re-shaded");
  EXPECT_NEAR(over["groups"][0]["fit"]["diffuse_gain"][0].get<double>(), 1.0, 1e-3) << "phongcl's own render: gain 1";
  EXPECT_EQ(over["groups"][1]["change"], "unchanged");

  // Muting a group takes its rendered pass out, exactly as the renderer's light mix does.
  put_json(client, "/api/scene", scene);
  put_json(client, "/api/settings", {{"mute", {"fill"}}});
  Image without_fill = render.combined;
  for (std::size_t i = 0; i < without_fill.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) without_fill.pixel(i)[c] -= render.passes.at("fill").pixel(i)[c];
  EXPECT_EQ(worst_covered_difference(served_exr(client), without_fill), 0.0f);
}

TEST(ServeOver, ScenesThatCannotBeCompositedAreRefusedAtThePut) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  testing::TempDir dir("serve_over_refused");
  json scene = grouped_scene();
  std::ofstream(dir / "scene.json") << scene.dump(1);
  const Render render = write_render(dir / "scene.json", dir / "render.exr");
  testing::RunningServer server(read_gbuffer(kGBufferFile), dir / "scene.json", {}, {}, dir / "render.exr");
  httplib::Client client = server.client();

  json unrendered = scene;
  unrendered.erase("rendered");
  auto result = client.Put("/api/scene", unrendered.dump(), "application/json");
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 400);
  EXPECT_NE(result->body.find("has no \\\"rendered\\\" lights"), std::string::npos) << result->body;

  json ungrouped = scene;
  ungrouped["lights"][0].erase("group");
  ungrouped["rendered"]["lights"][0].erase("group");
  ungrouped["lights"][0]["position"][1] = 7.0;
  result = client.Put("/api/scene", ungrouped.dump(), "application/json");
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 400);
  EXPECT_NE(result->body.find("a light in no light group differs"), std::string::npos) << result->body;
  EXPECT_EQ(worst_covered_difference(served_exr(client), render.combined), 0.0f) << "the held scene kept";
}

TEST(ServeOver, ARenderOfAnotherSizeIsRefusedAtStart) {
  testing::TempDir dir("serve_over_size");
  const Image small(4, 3);
  write_layered_exr({{"ViewLayer.Combined", &small, true}}, dir / "small.exr");
  try {
    RelightSession session(read_gbuffer(kGBufferFile), "", dir / "small.exr");
    FAIL() << "a 4 x 3 render over a 640 x 480 G-buffer was taken";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("small.exr: is 4 x 3, the G-buffer 640 x 480"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace phongcl
