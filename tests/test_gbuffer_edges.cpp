// What renderers' files hold at the edges of surfaces (gbuffer/edge_policy.h), on the Blender
// fixtures: sky samples, coverage, the policy measured against a supersampled render, and the
// policy on every layout and pass combination the readers accept (each renderer layout's naming,
// with or without a position pass, a material pass, alpha), which the sanitizer suite
// (scripts/checks/20-sanitizers.sh) runs under ASan and UBSan.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "blender_fixtures.h"
#include "cli_runner.h"
#include "exr/exr_channels.h"
#include "gbuffer/layouts.h"
#include "image/image.h"
#include "raycast/depth_reconstruction.h"
#include "reference/reference.h"
#include "renderer_files.h"
#include "shading_support.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

using namespace testing;


TEST(BlenderLayouts, SkySamplesAreBackgroundWhateverTheNormalSays) {
  const Passes p = read_passes(kFixtures / "cycles.exr", kCyclesChannels);
  const GBuffer g = read_gbuffer(kFixtures / "cycles.exr", {}).gbuffer;
  int sky_with_normal = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const std::size_t i = std::size_t(y) * p.width + x;
      const bool sky = p.at("ViewLayer.Depth.Z", x, y) == 1e10f;
      EXPECT_EQ(sky, g.material[i] < 0.0f) << "pixel " << x << "," << y;
      if (sky && glm::length(p.vec("ViewLayer.Normal", x, y)) > 0.0) {
        ++sky_with_normal;
        EXPECT_EQ(glm::length(p.vec("ViewLayer.Position", x, y)), 0.0) << "Cycles leaves P = 0 where the centre missed";
      }
    }
  EXPECT_GT(sky_with_normal, 10) << "the fixture has no horizon pixels with a filtered normal: it tests nothing";
  // EEVEE's no-hit depth is 65504.
  const Passes eevee = read_passes(kFixtures / "eevee.exr", {"ViewLayer.Depth.Z"});
  const GBuffer e = read_gbuffer(kFixtures / "eevee.exr", {}).gbuffer;
  for (std::size_t i = 0; i < e.pixel_count(); ++i)
    EXPECT_EQ(eevee.channels.at("ViewLayer.Depth.Z")[i] == 65504.0f, e.material[i] < 0.0f) << "pixel " << i;
}

TEST(BlenderLayouts, CoverageIsTheTransparentFilmsAlphaElseTheNormalsLength) {
  const Passes t = read_passes(kFixtures / "transparent.exr", kCyclesChannels);
  const GBufferRead transparent = read_gbuffer(kFixtures / "transparent.exr", {});
  EXPECT_NE(transparent.description.find("coverage from alpha"), std::string::npos) << transparent.description;
  const GBufferRead opaque = read_gbuffer(kFixtures / "cycles.exr", {});
  EXPECT_NE(opaque.description.find("coverage from the normal's length next to background"), std::string::npos)
      << opaque.description;
  const Passes o = read_passes(kFixtures / "cycles.exr", kCyclesChannels);
  int partial = 0;
  double spread = 0.0;
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      const std::size_t i = std::size_t(y) * t.width + x;
      if (transparent.gbuffer.material[i] < 0.0f) continue;
      EXPECT_FLOAT_EQ(transparent.gbuffer.coverage[i], t.at("ViewLayer.Combined.A", x, y));
      // Opaque film: the filtered normal's length, which on these surfaces is GlossCol's coverage
      // (GlossCol is 1 on every surface sample) to the spread of the normals in the footprint.
      // The average of unit normals is never longer than the fraction of samples that hit.
      const float c = opaque.gbuffer.coverage[i];
      if (c < 1.0f) {
        ++partial;
        const double gloss = o.at("ViewLayer.GlossCol.R", x, y);
        EXPECT_LE(c, gloss + 1e-3) << x << "," << y;
        spread += gloss - c;
      }
    }
  EXPECT_GT(partial, 10);
  EXPECT_LE(spread / partial, 0.03) << "mean shortfall of the normal's length against GlossCol's coverage";
}

// --- the edge policy, measured --------------------------------------------------------------------

// Pixels of `frame` (premultiplied RGB) outside the range of the premultiplied sub-samples of
// `sub` (4x the size) within +-0.75 px of their centre, by more than `margin` in any channel.
int outside_footprint(const Image& frame, const Image& sub, double margin) {
  int outside = 0;
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      // Sub-pixel i's centre is (i + 0.5) / 4: within 0.75 of x + 0.5 for i = 4x - 1 ... 4x + 4.
      glm::dvec3 low(1e30), high(-1e30);
      for (int j = std::max(4 * y - 1, 0); j <= std::min(4 * y + 4, sub.height - 1); ++j)
        for (int i = std::max(4 * x - 1, 0); i <= std::min(4 * x + 4, sub.width - 1); ++i) {
          const float* s = sub.pixel(std::size_t(j) * sub.width + i);
          for (int c = 0; c < 3; ++c) low[c] = std::min<double>(low[c], s[c]), high[c] = std::max<double>(high[c], s[c]);
        }
      const float* f = frame.pixel(std::size_t(y) * frame.width + x);
      bool out = false;
      for (int c = 0; c < 3; ++c) out |= f[c] < low[c] - margin || f[c] > high[c] + margin;
      outside += out;
    }
  return outside;
}

// The reading before the edge policy: background only where the normal is 0, every other pixel
// opaque with its centre sample's position and material and the filtered normal and DiffCol.
GBuffer without_edge_policy(const Passes& p) {
  GBuffer g;
  g.width = p.width;
  g.height = p.height;
  g.data_window = g.display_window = {0, 0, p.width - 1, p.height - 1};
  for (int c = 0; c < 3; ++c) {
    g.position[c] = p.channels.at(std::string("ViewLayer.Position.") + "XYZ"[c]);
    g.normal[c] = p.channels.at(std::string("ViewLayer.Normal.") + "XYZ"[c]);
    g.kd[c] = p.channels.at(std::string("ViewLayer.DiffCol.") + "RGB"[c]);
  }
  g.material = p.channels.at("ViewLayer.IndexMA.X");
  for (std::size_t i = 0; i < g.pixel_count(); ++i)
    if (g.normal[0][i] == 0.0f && g.normal[1][i] == 0.0f && g.normal[2][i] == 0.0f) g.material[i] = -1.0f;
  return g;
}

// The edge policy measured against the 4x4-supersampled render with the filter off (every sub-sample
// one centre sample, shaded on its own, premultiplied by its coverage: 1 on a surface, 0 on the
// sky), how many pixels take a colour outside every sub-sample's in their +-0.75 px footprint.
TEST(BlenderEdges, FewerPixelsOutsideTheirFootprintsRange) {
  const Scene scene = fixture_scene();
  const Image sub = reference_image(scene, read_gbuffer(kFixtures / "supersampled.exr", {}).gbuffer);
  const Passes p = read_passes(kFixtures / "cycles.exr", kCyclesChannels);
  const Image before = reference_image(scene, without_edge_policy(p));
  const Image after = reference_image(scene, read_gbuffer(kFixtures / "cycles.exr", {}).gbuffer);
  ASSERT_EQ(sub.width, 4 * before.width);
  const int before_005 = outside_footprint(before, sub, 0.05), after_005 = outside_footprint(after, sub, 0.05);
  const int before_01 = outside_footprint(before, sub, 0.1), after_01 = outside_footprint(after, sub, 0.1);
  int opaque_missed_before = 0, opaque_missed_after = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      if (p.at("ViewLayer.Depth.Z", x, y) < 65504.0f) continue;
      const std::size_t i = std::size_t(y) * p.width + x;
      opaque_missed_before += before.pixel(i)[3] > 0.0f;
      opaque_missed_after += after.pixel(i)[3] > 0.0f;
    }
  std::cout << "edge policy on the " << p.width << "x" << p.height << " Cycles fixture: outside the footprint's range by "
            << "> 0.05: " << before_005 << " before, " << after_005 << " after; by > 0.1: " << before_01 << " before, "
            << after_01 << " after; opaque pixels whose centre sample missed: " << opaque_missed_before << " before, "
            << opaque_missed_after << " after\n";
  EXPECT_GT(before_005, 20) << "the fixture shows no fringe to remove: it tests nothing";
  EXPECT_LE(5 * after_005, before_005);
  EXPECT_EQ(opaque_missed_after, 0);
}

// The kernel applies the edge policy as the reference does, on every pixel (partial coverage
// included): premultiplied colour, alpha = coverage.
TEST(BlenderEdges, KernelAndReferenceAgreeOnPartialPixels) {
  const Scene scene = fixture_scene();
  for (const char* file : {"cycles.exr", "transparent.exr"}) {
    SCOPED_TRACE(file);
    TempDir dir;
    const auto out = dir / "lit.exr";
    const auto run = run_phongcl("shade --scene tests/fixtures/blender/scene.json --gbuffer tests/fixtures/blender/" +
                                 std::string(file) + " --out " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const Image lit = read_exr(out);
    const GBuffer g = read_gbuffer(kFixtures / file, {}).gbuffer;
    const Image expected = reference_image(scene, g);
    int partial = 0;
    for (std::size_t i = 0; i < g.pixel_count(); ++i) {
      partial += g.has_coverage() && g.material[i] >= 0.0f && g.coverage[i] < 1.0f;
      ASSERT_EQ(lit.pixel(i)[3], expected.pixel(i)[3]) << "alpha (the coverage) of pixel " << i;
    }
    EXPECT_GT(partial, 10);
    const ErrorStats error = shading_error(lit, expected);
    EXPECT_LE(error.max_rel, kRelativeBound) << describe_worst(error);
  }
}

// Blender's passes as the combinations use them, and how each renderer layout names them: vectors
// get .X .Y .Z or .R .G .B (lower case for the custom mapping), scalars are named whole.
const char* const kPasses[] = {"Position", "Normal", "Depth", "IndexMA", "DiffCol", "Alpha"};

struct Naming {
  const char* layout;
  std::string prefix;
  std::array<std::string, 6> names;  // in kPasses' order
  bool lower_case = false;

  std::vector<std::string> channels(const std::string& pass) const {
    const std::size_t k = std::find(std::begin(kPasses), std::end(kPasses), pass) - std::begin(kPasses);
    const std::string base = prefix + names[k];
    if (pass == "Depth" || pass == "IndexMA" || pass == "Alpha") return {base};
    std::string axes = pass == "DiffCol" ? "RGB" : "XYZ";
    if (lower_case) std::transform(axes.begin(), axes.end(), axes.begin(), ::tolower);
    return {base + "." + axes[0], base + "." + axes[1], base + "." + axes[2]};
  }
};

const std::vector<Naming>& namings() {
  static const std::vector<Naming> all = {
      {"blender", "ViewLayer.", {"Position", "Normal", "Depth.Z", "IndexMA.X", "DiffCol", "Combined.A"}},
      {"blender File Output node", "", {"Position", "Normal", "Depth.V", "IndexMA.V", "DiffCol", "Alpha.V"}},
      {"aov", "", {"P", "N", "Z", "material", "diffuse_albedo", "A"}},
      {"custom (--channel)", "", {"pos", "nrm", "dist", "matid", "albedo", "cov"}, true},
  };
  return all;
}

struct Combination {
  const Naming* naming;
  bool position, material, alpha;
  std::string name() const {
    return std::string(naming->layout) + (position ? ", position" : ", depth only") + (material ? ", material" : "") +
           (alpha ? ", alpha" : "");
  }
};

// Writes a Cycles fixture's passes under the combination's names, leaving out what it lacks.
fs::path write_combination(const Combination& c, const Passes& cycles, const fs::path& dir) {
  std::vector<std::string> passes = {"Normal", "Depth", "DiffCol"};
  if (c.position) passes.push_back("Position");
  if (c.material) passes.push_back("IndexMA");
  if (c.alpha) passes.push_back("Alpha");
  std::vector<exr::WriteSlice> slices;
  for (const std::string& pass : passes) {
    const std::vector<std::string> names = c.naming->channels(pass), from = namings().front().channels(pass);
    for (std::size_t k = 0; k < names.size(); ++k) slices.push_back({names[k], cycles.channels.at(from[k]).data()});
  }
  const PixelWindow window{0, 0, cycles.width - 1, cycles.height - 1};
  const fs::path file = dir / (std::to_string(std::hash<std::string>{}(c.name())) + ".exr");
  exr::write_channels(file, window, window, ExrPixelType::float32, slices);
  return file;
}

ReadOptions options_for(const Combination& c) {
  ReadOptions options;
  const std::string layout = c.naming->layout;
  // Without P (or with a material pass) an aov file is not told from others by its names alone.
  if (layout == "aov") options.layout = Layout::aov;
  if (layout.rfind("custom", 0) == 0) {
    options.channels[Pass::normal] = c.naming->channels("Normal");
    options.channels[Pass::kd] = c.naming->channels("DiffCol");
    // Depth in both: it tells the sky samples (a custom mapping has no no-hit depth, the position
    // pass has zeros there), so the two read the same pixels as background.
    if (c.position) options.channels[Pass::position] = c.naming->channels("Position");
    options.channels[Pass::depth] = c.naming->channels("Depth");
    if (c.material) options.channels[Pass::material] = c.naming->channels("IndexMA");
    if (c.alpha) options.channels[Pass::alpha] = c.naming->channels("Alpha");
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

// A Cycles render without a Position pass used to end in SIGSEGV: the edge repair compared
// positions that were not rebuilt from depth yet. Every combination now reads, rebuilds and
// repairs, and the repair finds the same pixels whether positions come from the pass or from depth.
TEST(EdgePolicy, EveryLayoutAndPassCombinationIsRepairedAlike) {
  const Scene scene = fixture_scene();
  const Passes opaque = read_passes(kFixtures / "cycles.exr", kCyclesChannels);
  const Passes transparent = read_passes(kFixtures / "transparent.exr", kCyclesChannels);
  TempDir dir;
  int combinations = 0;
  for (const Naming& naming : namings())
    for (const bool alpha : {false, true})
      for (const bool material : {false, true}) {
        std::size_t repaired_with_position = 0;
        for (const bool position : {true, false}) {
          const Combination c{&naming, position, material, alpha};
          SCOPED_TRACE(c.name());
          GBufferRead read = read_gbuffer(write_combination(c, alpha ? transparent : opaque, dir.path), options_for(c));
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
  const Scene scene = fixture_scene();
  GBufferRead read = read_gbuffer(kFixtures / "cycles_depth.exr", ReadOptions{});
  ASSERT_TRUE(read.needs_positions_from_depth()) << read.description;
  positions_from_depth(read, scene.camera);
  EXPECT_NE(read.description.find("edge pixels between surfaces given their centre surface's normal"), std::string::npos)
      << read.description;
  const Passes cycles = read_passes(kFixtures / "cycles.exr", kCyclesChannels);
  const GBuffer& g = read.gbuffer;
  double worst = 0.0;
  std::size_t compared = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x;
      if (g.material[i] < 0.0f || !(cycles.at("ViewLayer.Depth.Z", x, y) < 65504.0f)) continue;
      const glm::dvec3 truth = cycles.vec("ViewLayer.Position", x, y);
      const glm::dvec3 rebuilt{g.position[0][i], g.position[1][i], g.position[2][i]};
      worst = std::max(worst, glm::length(rebuilt - truth) / glm::length(truth - scene.camera.eye));
      ++compared;
    }
  EXPECT_GT(compared, g.pixel_count() / 2);
  EXPECT_LE(worst, 2e-5) << "rebuilt positions against Cycles' Position pass, relative to the distance";

  TempDir dir;
  const auto run = run_phongcl("shade --scene tests/fixtures/blender/scene.json --gbuffer "
                               "tests/fixtures/blender/cycles_depth.exr --out " + (dir / "lit.exr").string());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(dir / "lit.exr")) << run.out;
}

}  // namespace
}  // namespace phongcl
