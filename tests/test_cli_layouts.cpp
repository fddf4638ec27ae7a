// `phongcl shade` on renderers' files: every layout shades with only --scene and --gbuffer, says
// which layout it read, and a bad layout or channel flag is a one-line error that keeps the output.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "image/image.h"
#include "renderer_files.h"
#include "shading_support.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using namespace testing;

std::string quoted(const fs::path& path) { return std::string("\"").append(path.string()).append("\""); }

TEST(LayoutsCli, RendererFilesShadeWithOnlySceneAndGBuffer) {
  PHONGCL_REQUIRE_DEVICE(shader);
  (void)shader;  // the binary opens the same default device itself
  TempDir dir;
  Scene scene = load_scene(kDefaultScene);  // the scene file's own camera and size
  const GBuffer g = generate_gbuffer(scene);
  write_gbuffer(g, dir / "native.exr");
  write_file(dir / "short.exr", g, blender_channels(scene, g, {}));
  write_file(dir / "long.exr", g, blender_channels(scene, g, {.long_names = true}));
  write_file(dir / "depth.exr", g, blender_channels(scene, g, {.position = false, .depth = DepthPass::view_z}));
  Channels aov;
  add3(aov, "P", "RGB", g.position);
  add3(aov, "N", "RGB", g.normal);
  aov.push_back({"material", material_index_pass(g)});
  write_file(dir / "aov.exr", g, aov);

  const std::string scene_arg = "--scene " + quoted(kDefaultScene);
  const CliRun native = run_phongcl("shade " + scene_arg + " --gbuffer " + quoted(dir / "native.exr") + " --out " +
                                    quoted(dir / "native_lit.exr"));
  ASSERT_EQ(native.exit_code, 0) << native.err;
  EXPECT_NE(native.out.find("  layout     phongcl (P, N, material)\n"), std::string::npos) << native.out;
  const Image expected = read_exr(dir / "native_lit.exr");

  write_gbuffer(in_camera_space(g, scene.camera), dir / "camera.exr");

  struct Case {
    const char *file, *flags, *announced;
  };
  for (const Case& c : {Case{"short.exr", "--ks-from pass", "layout     blender (view layer 'ViewLayer': Position, Normal, DiffCol, GlossCol, IndexMA"},
                        Case{"long.exr", "--ks-from pass", "layout     blender (view layer 'ViewLayer': Position, Normal, Diffuse Color, Glossy Color, Material Index"},
                        Case{"depth.exr", "", "positions from depth; kd from DiffCol, ks from the scene's table; GlossCol not used as ks (--ks-from pass uses it)), depth = view-space z (Blender's Depth pass is view-space z; --depth-convention overrides)"},
                        Case{"aov.exr", "", "layout     aov (P, N, material)"},
                        Case{"camera.exr", "--space camera", "space      camera"}}) {
    SCOPED_TRACE(c.file);
    const CliRun run = run_phongcl("shade " + scene_arg + " --gbuffer " + quoted(dir / c.file) + " --out " +
                                   quoted(dir / "lit.exr") + " --aov " + quoted(dir / "aov_out.exr") + " " + c.flags);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find(c.announced), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("aov_out.exr (ambient, diffuse, specular + combined, float32)"), std::string::npos) << run.out;
    const ErrorStats stats = shading_error(read_exr(dir / "lit.exr"), expected, shaded_mask(g));
    // Per-pixel colours instead of the table, positions rebuilt from depth or moved into camera
    // space (a few ulps of P and N): well inside the kernel's own bound.
    EXPECT_LE(stats.max_rel, kRelativeBound) << describe_worst(stats);
    const ErrorStats combined = shading_error(read_exr(dir / "aov_out.exr"), read_exr(dir / "lit.exr"));
    EXPECT_EQ(combined.max_abs, 0.0) << "the AOV file's R G B A is the combined image";
  }
}

TEST(LayoutsCli, BadLayoutOrChannelIsOneLineAndKeepsTheOutput) {
  TempDir dir;
  const Scene scene = load_scene(kDefaultScene);
  const auto [small_scene, g] = default_scene();
  write_file(dir / "b.exr", g, blender_channels(small_scene, g, {}));
  std::ofstream(dir / "lit.exr") << "previous result";
  const std::string common = "shade --scene " + quoted(kDefaultScene) + " --gbuffer " + quoted(dir / "b.exr") +
                             " --out " + quoted(dir / "lit.exr");
  struct Case {
    std::string flags;
    std::vector<std::string> expected;
  };
  for (const Case& c : {Case{"--layout maya", {"unknown --layout 'maya' (choose auto, phongcl, blender or aov)"}},
                        Case{"--channel position=Foo.X,Foo.Y,Foo.Z",
                             {(dir / "b.exr").string(), "--channel position: no channel 'Foo.X'", "found: ", "ViewLayer.Normal.X"}},
                        Case{"--channel colour=A", {"unknown pass 'colour'"}},
                        Case{"--layout aov", {(dir / "b.exr").string(), "missing channels P.X, P.Y, P.Z"}},
                        Case{"--view-layer Missing", {"missing channels Missing.Position.X"}}}) {
    SCOPED_TRACE(c.flags);
    const CliRun run = run_phongcl(common + " " + c.flags);
    EXPECT_NE(run.exit_code, 0);
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    for (const auto& part : c.expected) EXPECT_NE(run.err.find(part), std::string::npos) << run.err;
    EXPECT_EQ(read_text(dir / "lit.exr"), "previous result");
  }
}

}  // namespace
}  // namespace phongcl
