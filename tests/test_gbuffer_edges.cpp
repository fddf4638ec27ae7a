// The edge policy (gbuffer/edge_policy.h) on every layout and pass combination the readers accept:
// each renderer layout's naming, with or without a position pass (positions then come from depth),
// with or without a material pass, with or without alpha. The passes are Blender's own (the Cycles
// fixtures of tests/fixtures/blender), renamed and left out to make each combination; the
// sanitizer suite (scripts/checks/20-sanitizers.sh) runs these reads under ASan and UBSan.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "exr/exr_channels.h"
#include "gbuffer/layouts.h"
#include "raycast/depth_reconstruction.h"
#include "scene/scene.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;

const fs::path kFixtures = fs::path(PHONGCL_SOURCE_DIR) / "tests/fixtures/blender";

// The passes of one Blender file, by pass ("Normal") and channel ("X").
struct Passes {
  PixelWindow data_window, display_window;
  std::map<std::string, Plane> planes;  // "Normal.X" -> values
};

Passes read_blender(const fs::path& file) {
  exr::InputExr input(file);
  Passes passes{input.data_window(), input.display_window(), {}};
  const std::size_t pixels = static_cast<std::size_t>(passes.data_window.width()) * passes.data_window.height();
  std::vector<exr::ReadSlice> slices;
  const std::string layer = "ViewLayer.";
  for (const std::string& name : input.channel_names()) {
    if (name.rfind(layer, 0) != 0) continue;
    Plane& plane = passes.planes[name.substr(layer.size())];
    plane.resize(pixels);
    slices.push_back({name, plane.data()});
  }
  input.read(slices);
  return passes;
}

// How a renderer layout names each pass (empty: the layout has no name for it).
struct Naming {
  const char* layout;
  std::map<std::string, std::vector<std::string>> names;  // Blender pass -> this layout's channels
};

std::vector<std::string> suffixed(const std::string& base, const char* a, const char* b, const char* c) {
  return {base + a, base + b, base + c};
}

const std::vector<Naming>& namings() {
  static const std::vector<Naming> all = {
      {"blender",
       {{"Position", suffixed("ViewLayer.Position", ".X", ".Y", ".Z")},
        {"Normal", suffixed("ViewLayer.Normal", ".X", ".Y", ".Z")},
        {"Depth", {"ViewLayer.Depth.Z"}},
        {"IndexMA", {"ViewLayer.IndexMA.X"}},
        {"DiffCol", suffixed("ViewLayer.DiffCol", ".R", ".G", ".B")},
        {"Alpha", {"ViewLayer.Combined.A"}}}},
      {"blender File Output node",
       {{"Position", suffixed("Position", ".X", ".Y", ".Z")},
        {"Normal", suffixed("Normal", ".X", ".Y", ".Z")},
        {"Depth", {"Depth.V"}},
        {"IndexMA", {"IndexMA.V"}},
        {"DiffCol", suffixed("DiffCol", ".R", ".G", ".B")},
        {"Alpha", {"Alpha.V"}}}},
      {"aov",
       {{"Position", suffixed("P", ".X", ".Y", ".Z")},
        {"Normal", suffixed("N", ".X", ".Y", ".Z")},
        {"Depth", {"Z"}},
        {"IndexMA", {"material"}},
        {"DiffCol", suffixed("diffuse_albedo", ".R", ".G", ".B")},
        {"Alpha", {"A"}}}},
      {"custom (--channel)",
       {{"Position", suffixed("pos", ".x", ".y", ".z")},
        {"Normal", suffixed("nrm", ".x", ".y", ".z")},
        {"Depth", {"dist"}},
        {"IndexMA", {"matid"}},
        {"DiffCol", suffixed("albedo", ".r", ".g", ".b")},
        {"Alpha", {"cov"}}}},
  };
  return all;
}

// Blender's pass and channel names ("Normal" -> "Normal.X", "Normal.Y", "Normal.Z").
std::vector<std::string> blender_channels(const std::string& pass) {
  if (pass == "Depth") return {"Depth.Z"};
  if (pass == "IndexMA") return {"IndexMA.X"};
  if (pass == "Alpha") return {"Combined.A"};
  if (pass == "DiffCol") return suffixed(pass, ".R", ".G", ".B");
  return suffixed(pass, ".X", ".Y", ".Z");
}

struct Combination {
  const Naming* naming;
  bool position, material, alpha;
  std::string name() const {
    return std::string(naming->layout) + (position ? ", position" : ", depth only") + (material ? ", material" : "") +
           (alpha ? ", alpha" : "");
  }
};

// Writes `source`'s passes under the combination's names, leaving out what it lacks.
fs::path write_combination(const Combination& c, const Passes& source, const fs::path& dir) {
  std::vector<std::string> passes = {"Normal", "Depth", "DiffCol"};
  if (c.position) passes.push_back("Position");
  if (c.material) passes.push_back("IndexMA");
  if (c.alpha) passes.push_back("Alpha");
  std::vector<exr::WriteSlice> slices;
  for (const std::string& pass : passes) {
    const std::vector<std::string> names = c.naming->names.at(pass), from = blender_channels(pass);
    for (std::size_t k = 0; k < names.size(); ++k) slices.push_back({names[k], source.planes.at(from[k]).data()});
  }
  const fs::path file = dir / (std::to_string(std::hash<std::string>{}(c.name())) + ".exr");
  exr::write_channels(file, source.data_window, source.display_window, ExrPixelType::float32, slices);
  return file;
}

ReadOptions options_for(const Combination& c) {
  ReadOptions options;
  const std::string layout = c.naming->layout;
  // Without P (or with a material pass) an aov file is not told from others by its names alone.
  if (layout == "aov") options.layout = Layout::aov;
  if (layout.rfind("custom", 0) == 0) {
    options.channels[Pass::normal] = c.naming->names.at("Normal");
    options.channels[Pass::kd] = c.naming->names.at("DiffCol");
    // Depth in both: it tells the sky samples (a custom mapping has no no-hit depth, the position
    // pass has zeros there), so the two read the same pixels as background.
    if (c.position) options.channels[Pass::position] = c.naming->names.at("Position");
    options.channels[Pass::depth] = c.naming->names.at("Depth");
    if (c.material) options.channels[Pass::material] = c.naming->names.at("IndexMA");
    if (c.alpha) options.channels[Pass::alpha] = c.naming->names.at("Alpha");
  }
  // Every file here holds Blender's view-space z, whatever the layout's default.
  options.depth_convention = DepthConvention::view_z;
  return options;
}

std::size_t repaired_count(const std::string& description) {
  const std::size_t at = description.find(" edge pixels between surfaces");
  if (at == std::string::npos) return 0;
  const std::size_t begin = description.rfind(", ", at) + 2;
  return std::stoul(description.substr(begin, at - begin));
}

// A Cycles render without a Position pass (Blender's default) used to end in SIGSEGV: the edge
// repair compared positions that were not rebuilt from depth yet. Every combination now reads,
// rebuilds and repairs; the repair finds the same pixels whether positions come from the pass or
// from depth, and gives each a full-length normal from a neighbour.
TEST(EdgePolicy, EveryLayoutAndPassCombinationIsRepairedAlike) {
  const Scene scene = load_scene(kFixtures / "scene.json");
  const Passes opaque = read_blender(kFixtures / "cycles.exr");
  const Passes transparent = read_blender(kFixtures / "transparent.exr");
  testing::TempDir dir("edges");
  int combinations = 0;
  for (const Naming& naming : namings())
    for (const bool alpha : {false, true})
      for (const bool material : {false, true}) {
        std::size_t repaired_with_position = 0;
        for (const bool position : {true, false}) {
          const Combination c{&naming, position, material, alpha};
          SCOPED_TRACE(c.name());
          const Passes& source = alpha ? transparent : opaque;
          GBufferRead read = read_gbuffer(write_combination(c, source, dir.path), options_for(c));
          ASSERT_EQ(read.needs_positions_from_depth(), !position) << read.description;
          if (!position) {
            EXPECT_TRUE(read.edges_need_positions);
            positions_from_depth(read, scene.camera);
            EXPECT_FALSE(read.edges_need_positions);
          }
          const GBuffer& g = read.gbuffer;
          std::size_t shaded = 0;
          for (std::size_t i = 0; i < g.pixel_count(); ++i) {
            if (g.material[i] < 0.0f) continue;
            ++shaded;
            for (int axis = 0; axis < 3; ++axis) ASSERT_TRUE(std::isfinite(g.position[axis][i])) << "pixel " << i;
          }
          EXPECT_GT(shaded, g.pixel_count() / 4) << read.description;
          const std::size_t repaired = repaired_count(read.description);
          EXPECT_GT(repaired, 0u) << "Cycles' filtered normals mix surfaces at some edge: " << read.description;
          if (position) repaired_with_position = repaired;
          else EXPECT_EQ(repaired, repaired_with_position) << read.description;
          ++combinations;
        }
      }
  EXPECT_EQ(combinations, 32);
}

// The render the crash came from: Blender 3.4's Cycles with its default passes and Normal, IndexMA,
// DiffCol, GlossCol (scripts/blender/make_fixtures.py, cycles_depth.exr). It shades with no flags,
// and its positions, rebuilt from Depth, are where the Cycles render with a Position pass (same
// camera, same first sample: the two Depth passes are equal) saw each pixel: within 2e-5 of the
// distance, Cycles' shadow terminator offset (its Position pass moves smooth-shaded surfaces such
// as the sphere by about 1e-5 of the distance along the normal; flat ones agree to 2e-6).
TEST(EdgePolicy, CyclesRenderWithoutPositionShades) {
  const Scene scene = load_scene(kFixtures / "scene.json");
  GBufferRead read = read_gbuffer(kFixtures / "cycles_depth.exr", ReadOptions{});
  ASSERT_TRUE(read.needs_positions_from_depth()) << read.description;
  positions_from_depth(read, scene.camera);
  EXPECT_NE(read.description.find("edge pixels between surfaces given their centre surface's normal"), std::string::npos)
      << read.description;
  const Passes with_position = read_blender(kFixtures / "cycles.exr");
  const GBuffer& g = read.gbuffer;
  double worst = 0.0;
  std::size_t compared = 0;
  for (std::size_t i = 0; i < g.pixel_count(); ++i) {
    if (g.material[i] < 0.0f || with_position.planes.at("Depth.Z")[i] >= 65504.0f) continue;
    double apart = 0.0, distance = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double truth = with_position.planes.at(std::string("Position.") + "XYZ"[axis])[i];
      apart += (g.position[axis][i] - truth) * (g.position[axis][i] - truth);
      distance += (truth - scene.camera.eye[axis]) * (truth - scene.camera.eye[axis]);
    }
    worst = std::max(worst, std::sqrt(apart / distance));
    ++compared;
  }
  EXPECT_GT(compared, g.pixel_count() / 2);
  EXPECT_LE(worst, 2e-5) << "rebuilt positions against Cycles' Position pass, relative to the distance";

  testing::TempDir dir("edges_cli");
  const auto run = testing::run_phongcl("shade --scene tests/fixtures/blender/scene.json --gbuffer "
                                        "tests/fixtures/blender/cycles_depth.exr --out " + (dir / "lit.exr").string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(dir / "lit.exr")) << run.out;
}

}  // namespace
}  // namespace phongcl
