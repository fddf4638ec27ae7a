// Relighting over a render (host/composite, shade --over): which light groups an edit changed, the
// composite's arithmetic on premultiplied passes, reading a render's passes, and, end to end, a
// "render" made by phongcl itself: over it, no edit gives the render to the bit, and a moved or
// recoloured light gives phongcl's own shading of the edited scene to float rounding (the fit of a
// render that is phongcl's shading is a gain of 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "common/error.h"
#include "composite/composite.h"
#include "composite/group_edits.h"
#include "composite/group_fit.h"
#include "composite/render_passes.h"
#include "exr/exr_channels.h"
#include "image/image.h"
#include "input_error_of.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;
using testing::input_error_of;
using testing::TempDir;

Light grouped_light(const std::string& group, glm::dvec3 position, glm::dvec3 color) {
  Light light;
  light.position = position;
  light.color = color;
  light.group = group;
  return light;
}

// Three groups of one light each and one light in none, rendered as they are now.
Scene grouped_scene() {
  Scene scene;
  scene.source = "grouped.json";
  scene.lights = {grouped_light("key", {2, 3, 4}, {1, 0.9, 0.8}), grouped_light("fill", {-3, 1, 2}, {0.2, 0.3, 0.4}),
                  grouped_light("rim", {0, 4, -3}, {0.5, 0.5, 0.5}), grouped_light("", {0, 9, 0}, {0.1, 0.1, 0.1})};
  AreaLight panel;
  panel.group = "fill";
  scene.area_lights = {panel};
  scene.rendered = RenderedLights{scene.lights, scene.area_lights};
  return scene;
}

GroupEdit edit_of(const std::vector<GroupEdit>& edits, const std::string& group) {
  for (const GroupEdit& edit : edits)
    if (edit.group == group) return edit;
  ADD_FAILURE() << "no edit for group " << group;
  return {};
}

TEST(GroupEdits, UnchangedScaledAndReshadedGroups) {
  Scene scene = grouped_scene();
  for (const GroupEdit& edit : group_edits(scene)) EXPECT_EQ(edit.change, GroupChange::unchanged) << edit.group;

  scene.lights[0].color *= 2.0;                          // key: brighter, same hue
  scene.lights[1].color *= glm::dvec3(1.0, 0.5, 2.0);    // fill: the light and the panel by the same factors
  scene.area_lights[0].color *= glm::dvec3(1.0, 0.5, 2.0);
  scene.lights[2].position.x += 0.5;                     // rim: moved
  const std::vector<GroupEdit> edits = group_edits(scene);
  ASSERT_EQ(edits.size(), 3u);
  EXPECT_EQ(edit_of(edits, "key").change, GroupChange::scaled);
  EXPECT_EQ(edit_of(edits, "key").scale, glm::dvec3(2.0));
  EXPECT_EQ(edit_of(edits, "fill").change, GroupChange::scaled);
  EXPECT_EQ(edit_of(edits, "fill").scale, glm::dvec3(1.0, 0.5, 2.0));
  EXPECT_EQ(edit_of(edits, "rim").change, GroupChange::reshaded);
}

TEST(GroupEdits, ColourChangesThatNoOneFactorExplainsAreReshaded) {
  Scene scene = grouped_scene();
  scene.lights[1].color *= 2.0;  // the fill light, not its panel
  EXPECT_EQ(edit_of(group_edits(scene), "fill").change, GroupChange::reshaded);

  scene = grouped_scene();
  scene.rendered->lights[0].color = {1, 0, 0.8};  // rendered without green: nothing to scale up
  scene.lights[0].color = {1, 0.5, 0.8};
  EXPECT_EQ(edit_of(group_edits(scene), "key").change, GroupChange::reshaded);
  scene.lights[0].color = {2, 0, 1.6};
  EXPECT_EQ(edit_of(group_edits(scene), "key").change, GroupChange::scaled);
  EXPECT_EQ(edit_of(group_edits(scene), "key").scale, glm::dvec3(2.0, 1.0, 2.0));
}

TEST(GroupEdits, AddedAndRemovedGroupsAreReshaded) {
  Scene scene = grouped_scene();
  scene.lights.erase(scene.lights.begin() + 2);  // rim gone
  scene.lights.push_back(grouped_light("new", {1, 1, 1}, {1, 1, 1}));
  const std::vector<GroupEdit> edits = group_edits(scene);
  EXPECT_EQ(edit_of(edits, "rim").change, GroupChange::reshaded);
  EXPECT_EQ(edit_of(edits, "new").change, GroupChange::reshaded);
  EXPECT_EQ(edits.back().group, "rim") << "groups only the render had come last";
}

TEST(GroupEdits, LightsOutsideEveryGroupCannotBeEdited) {
  Scene scene = grouped_scene();
  scene.lights[3].color *= 2.0;
  EXPECT_NE(input_error_of([&] { group_edits(scene); }).find("grouped.json: a light in no light group differs"),
            std::string::npos);
  scene = grouped_scene();
  scene.lights.push_back(grouped_light("", {1, 1, 1}, {1, 1, 1}));
  EXPECT_NE(input_error_of([&] { group_edits(scene); }).find("a light in no light group differs"), std::string::npos);
  scene.rendered.reset();
  EXPECT_NE(input_error_of([&] { group_edits(scene); }).find("has no \"rendered\" lights"), std::string::npos);
}

Image filled(int width, int height, float r, float g, float b, float a) {
  Image image(width, height);
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    float* p = image.pixel(i);
    p[0] = r * (1 + i), p[1] = g * (1 + i), p[2] = b * (1 + i), p[3] = a;
  }
  return image;
}

TEST(GroupFit, DiffuseAndSpecularGainsOfTheRenderedPass) {
  // phongcl's rim as rendered, and a pass that is twice its diffuse plus half its specular light.
  GroupTerms rim{filled(3, 2, 0.05f, 0.05f, 0.05f, 0.5f), filled(3, 2, 0.05f, 0.05f, 0.05f, 0.5f)};
  for (std::size_t i = 0; i < 6; ++i)  // specular not a multiple of diffuse, so the two gains are apart
    for (int c = 0; c < 3; ++c) rim.specular.pixel(i)[c] *= static_cast<float>(1 + i % 3 + c);
  Image pass(3, 2);
  for (std::size_t i = 0; i < 6; ++i)
    for (int c = 0; c < 3; ++c) pass.pixel(i)[c] = 2.0f * rim.diffuse.pixel(i)[c] + 0.5f * rim.specular.pixel(i)[c];
  const GroupFit fit = fit_group(pass, rim);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(fit.diffuse_gain[c], 2.0, 1e-4) << c;
    EXPECT_NEAR(fit.specular_gain[c], 0.5, 1e-4) << c;
  }
  EXPECT_NEAR(fit.residual, 0.0, 1e-5);
  EXPECT_EQ(fit.pixels, 6u);

  // A pass that falls where phongcl's specular rises: the best gains have a negative specular one,
  // which light cannot have; the specular gain is 0 and the diffuse fitted alone.
  for (std::size_t i = 0; i < 6; ++i)
    for (int c = 0; c < 3; ++c) pass.pixel(i)[c] = 2.0f * rim.diffuse.pixel(i)[c] - 0.1f * rim.specular.pixel(i)[c];
  const GroupFit bounded = fit_group(pass, rim);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(bounded.specular_gain[c], 0.0) << c;
    EXPECT_GT(bounded.diffuse_gain[c], 0.0) << c;
  }
  EXPECT_THROW(fit_group(Image(2, 2), rim), std::invalid_argument);
}

TEST(CompositeOver, KeepsScalesAndChangesPassesOnPremultipliedValues) {
  RenderPasses render;
  render.combined = filled(3, 2, 1.0f, 2.0f, 3.0f, 0.5f);
  render.group_passes["key"] = filled(3, 2, 0.25f, 0.5f, 0.75f, 0.0f);
  render.group_passes["rim"] = filled(3, 2, 0.125f, 0.125f, 0.125f, 0.0f);
  // phongcl's fitted light of the rim as rendered and as edited.
  const Image then = filled(3, 2, 0.1f, 0.1f, 0.1f, 0.5f), now = filled(3, 2, 0.5f, 0.25f, 0.0f, 0.5f);
  const std::map<std::string, ChangedGroup> changed = {{"rim", {&then, &now}}};

  const Image same = composite_over(render, {{"key"}, {"rim"}}, changed);
  EXPECT_EQ(same.rgba, render.combined.rgba) << "nothing changed: the render, bit for bit";

  const Image out =
      composite_over(render, {{"key", GroupChange::scaled, {2.0, 1.0, 0.0}}, {"rim", GroupChange::reshaded}}, changed);
  for (std::size_t i = 0; i < out.pixel_count(); ++i) {
    const float* c = render.combined.pixel(i);
    const float* key = render.group_passes["key"].pixel(i);
    float expected[3] = {c[0] + key[0], c[1], c[2] - key[2]};
    for (int k = 0; k < 3; ++k) expected[k] += now.pixel(i)[k] - then.pixel(i)[k];
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(out.pixel(i)[k], expected[k], 1e-5) << "pixel " << i << " channel " << k;
    EXPECT_EQ(out.pixel(i)[3], c[3]) << "alpha is the render's";
  }
  // Made in a canvas of the render's size: the same image.
  EXPECT_EQ(composite_over(render, {{"key", GroupChange::scaled, {2.0, 1.0, 0.0}}, {"rim", GroupChange::reshaded}},
                           changed, Image(3, 2)).rgba,
            out.rgba);

  // A group whose lights are all gone: its rendered light taken out, exactly.
  const Image& rim = render.group_passes["rim"];
  const Image removed = composite_over(render, {{"rim", GroupChange::reshaded}}, {{"rim", {&then, nullptr}}});
  EXPECT_EQ(removed.pixel(0)[0], render.combined.pixel(0)[0] - rim.pixel(0)[0]);
  // A group the render did not have: phongcl's light added as it is.
  const Image added = composite_over(render, {{"new", GroupChange::reshaded}}, {{"new", {nullptr, &now}}});
  EXPECT_FLOAT_EQ(added.pixel(1)[2], render.combined.pixel(1)[2] + now.pixel(1)[2]);

  const Image small(2, 2);
  EXPECT_THROW(composite_over(render, {{"rim", GroupChange::reshaded}}, {{"rim", {&then, &small}}}), std::invalid_argument);
  EXPECT_THROW(composite_over(render, {{"fill", GroupChange::scaled, {2, 2, 2}}}, changed), std::invalid_argument);
  EXPECT_THROW(composite_over(render, {{"rim", GroupChange::reshaded}}, {}), std::invalid_argument);
  EXPECT_THROW(composite_over(render, {{"rim", GroupChange::reshaded}}, {{"rim", {nullptr, &now}}}), std::invalid_argument);
}

void write_render(const fs::path& file, const std::vector<std::pair<std::string, const Image*>>& passes) {
  std::vector<ExrLayer> layers;
  for (const auto& [name, image] : passes) layers.push_back({name, image, name.find("Combined_") == std::string::npos});
  ExrWriteOptions options;
  options.keep_color_where_transparent = true;
  write_layered_exr(layers, file, options);
}

TEST(RenderPasses, CombinedAndGroupPassesOfOneViewLayer) {
  TempDir dir;
  const Image combined = filled(4, 3, 1, 2, 3, 1), key = filled(4, 3, 0.5f, 0.5f, 0.5f, 0);
  write_render(dir / "render.exr", {{"ViewLayer.Combined", &combined}, {"ViewLayer.Combined_key", &key}});
  const RenderPasses passes = read_render_passes(dir / "render.exr", {"key"});
  EXPECT_EQ(passes.layer, "ViewLayer.");
  EXPECT_EQ(passes.combined.rgba, combined.rgba);
  ASSERT_EQ(passes.group_passes.count("key"), 1u);
  EXPECT_EQ(passes.group_passes.at("key").pixel(5)[1], key.pixel(5)[1]);

  EXPECT_NE(input_error_of([&] { read_render_passes(dir / "render.exr", {"rim"}); })
                .find("render.exr: no pass for light group 'rim' (ViewLayer.Combined_rim.R, G, B)"),
            std::string::npos);
  write_render(dir / "two.exr", {{"A.Combined", &combined}, {"B.Combined", &combined}});
  EXPECT_NE(input_error_of([&] { read_render_passes(dir / "two.exr", {}); }).find("more than one view layer (A., B.)"),
            std::string::npos);
  write_render(dir / "none.exr", {{"ViewLayer.Diffuse", &combined}});
  EXPECT_NE(input_error_of([&] { read_render_passes(dir / "none.exr", {}); }).find("none.exr: no Combined pass"),
            std::string::npos);
}

// ---- End to end: shade --over a render that phongcl made ----

nlohmann::json default_scene_with_groups() {
  std::ifstream in(PHONGCL_SOURCE_DIR "/scenes/default/scene.json");
  nlohmann::json scene = nlohmann::json::parse(in);
  scene["gbuffer"] = PHONGCL_SOURCE_DIR "/scenes/default/gbuffer.exr";
  const char* groups[] = {"key", "fill", "rim"};
  for (std::size_t i = 0; i < scene["lights"].size(); ++i) scene["lights"][i]["group"] = groups[i % 3];
  scene["rendered"] = {{"lights", scene["lights"]}};
  return scene;
}

void save(const nlohmann::json& scene, const fs::path& file) { std::ofstream(file) << scene.dump(1); }

float worst_difference(const Image& a, const Image& b) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]) / std::max(1.0f, std::abs(b.rgba[i])));
  return worst;
}

TEST(ShadeOver, NoEditGivesTheRenderAndEditsGivePhongclsOwnShading) {
  if (!testing::have_opencl_device()) GTEST_SKIP() << "no OpenCL device";
  TempDir dir;
  const nlohmann::json rendered = default_scene_with_groups();
  save(rendered, dir / "rendered.json");
  const auto shade = [&](const std::string& arguments) {
    const testing::CliRun run = testing::run_phongcl("shade " + arguments);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return run;
  };
  shade("--scene '" + (dir / "rendered.json").string() + "' --out '" + (dir / "full.exr").string() + "' --aov '" +
        (dir / "aov.exr").string() + "'");
  const Image full = read_exr(dir / "full.exr");
  std::vector<Image> groups;
  for (const char* group : {"key", "fill", "rim"}) {
    exr::InputExr aov(dir / "aov.exr");
    Image pass(full.width, full.height);
    std::vector<exr::ReadSlice> slices;
    for (int c = 0; c < 3; ++c) slices.push_back({std::string("group.") + group + "." + "RGB"[c], pass.rgba.data() + c, 4});
    aov.read(slices);
    groups.push_back(std::move(pass));
  }
  write_render(dir / "render.exr", {{"ViewLayer.Combined", &full}, {"ViewLayer.Combined_key", &groups[0]},
                                    {"ViewLayer.Combined_fill", &groups[1]}, {"ViewLayer.Combined_rim", &groups[2]}});
  const std::string over = " --over '" + (dir / "render.exr").string() + "'";

  const testing::CliRun same = shade("--scene '" + (dir / "rendered.json").string() + "' --out '" +
                                     (dir / "same.exr").string() + "'" + over);
  EXPECT_NE(same.out.find("key unchanged, fill unchanged, rim unchanged"), std::string::npos) << same.out;
  EXPECT_EQ(read_exr(dir / "same.exr").rgba, full.rgba) << "no edit: the render, bit for bit";

  nlohmann::json edited = rendered;
  edited["lights"][0]["position"][0] = edited["lights"][0]["position"][0].get<double>() + 0.5;  // key moved
  for (auto& component : edited["lights"][1]["color"]) component = component.get<double>() * 2.0;  // fill brighter
  save(edited, dir / "edited.json");
  const testing::CliRun composite = shade("--scene '" + (dir / "edited.json").string() + "' --out '" +
                                          (dir / "over.exr").string() + "'" + over);
  EXPECT_NE(composite.out.find("key changed by phongcl's change (fit: diffuse x(1, 1, 1), specular x(1, 1, 1), residual "),
            std::string::npos)
      << composite.out;
  EXPECT_NE(composite.out.find("fill scaled x(2, 2, 2), rim unchanged"), std::string::npos) << composite.out;
  shade("--scene '" + (dir / "edited.json").string() + "' --out '" + (dir / "direct.exr").string() + "'");
  // The render is phongcl's, so the composite is phongcl's shading of the edited scene, summed in
  // another order: within a few float roundings of the pixel's value.
  EXPECT_LT(worst_difference(read_exr(dir / "over.exr"), read_exr(dir / "direct.exr")), 1e-5f);
}

TEST(ShadeOver, ClearErrorsAndNothingWritten) {
  if (!testing::have_opencl_device()) GTEST_SKIP() << "no OpenCL device";
  TempDir dir;
  nlohmann::json scene = default_scene_with_groups();
  scene["lights"][0]["position"][0] = 9.0;
  save(scene, dir / "scene.json");
  const Image combined = filled(4, 3, 1, 2, 3, 1);
  write_render(dir / "small.exr", {{"ViewLayer.Combined", &combined}, {"ViewLayer.Combined_key", &combined}});
  const std::string base = "shade --scene '" + (dir / "scene.json").string() + "' --out '" + (dir / "out.exr").string() + "'";
  const testing::CliRun small = testing::run_phongcl(base + " --over '" + (dir / "small.exr").string() + "'");
  EXPECT_NE(small.exit_code, 0);
  EXPECT_NE(small.err.find("small.exr: "), std::string::npos) << small.err;
  EXPECT_NE(small.err.find("is 4 x 3, the G-buffer"), std::string::npos) << small.err;
  const testing::CliRun absent = testing::run_phongcl(base + " --over '" + (dir / "absent.exr").string() + "'");
  EXPECT_NE(absent.exit_code, 0);
  EXPECT_NE(absent.err.find("absent.exr"), std::string::npos) << absent.err;
  const testing::CliRun itself = testing::run_phongcl(base + " --over '" + (dir / "out.exr").string() + "'");
  EXPECT_NE(itself.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

}  // namespace
}  // namespace phongcl
