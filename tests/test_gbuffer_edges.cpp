// What renderers' files hold at the edges of surfaces (gbuffer/edge_policy.h), on the Blender
// fixtures: sky samples, coverage, and the policy measured against a supersampled render.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <string>

#include <glm/glm.hpp>

#include "blender_fixtures.h"
#include "cli_runner.h"
#include "gbuffer/layouts.h"
#include "image/image.h"
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

}  // namespace
}  // namespace phongcl
