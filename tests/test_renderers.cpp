// Real renderers' files: the Blender fixtures of tests/fixtures/blender (made by
// scripts/blender/make_fixtures.py with Blender 3.4: Cycles multilayer, the same passes through a
// File Output node, EEVEE depth-only, a transparent film, and a 4x supersampled Cycles frame with
// the pixel filter off). Each is read and shaded as a user would, and checked against the passes
// read here straight through OpenEXR.
#include <gtest/gtest.h>

#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>

#include <fstream>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "common/error.h"
#include "gbuffer/file_camera.h"
#include "raycast/raycast.h"
#include "gbuffer/layouts.h"
#include "image/image.h"
#include "reference/reference.h"
#include "scene/scene.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;
using testing::run_phongcl;

const fs::path kFixtures = fs::path(PHONGCL_SOURCE_DIR) / "tests/fixtures/blender";

struct TempDir : testing::TempDir {
  TempDir() : testing::TempDir("renderers") {}
};

// A file's channels as OpenEXR decodes them (float), by name, without phongcl's reader.
struct Passes {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> channels;

  float at(const std::string& name, int x, int y) const { return channels.at(name)[std::size_t(y) * width + x]; }
  glm::dvec3 vec(const std::string& base, int x, int y, const char* suffixes = "XYZ") const {
    return {at(base + "." + suffixes[0], x, y), at(base + "." + suffixes[1], x, y), at(base + "." + suffixes[2], x, y)};
  }
};

Passes read_passes(const fs::path& file, const std::vector<std::string>& names) {
  Imf::InputFile input(file.c_str());
  const Imath::Box2i window = input.header().dataWindow();
  Passes passes;
  passes.width = window.max.x - window.min.x + 1;
  passes.height = window.max.y - window.min.y + 1;
  Imf::FrameBuffer frame;
  for (const auto& name : names) {
    auto& plane = passes.channels[name];
    plane.resize(std::size_t(passes.width) * passes.height);
    frame.insert(name, Imf::Slice::Make(Imf::FLOAT, plane.data(), window));
  }
  input.setFrameBuffer(frame);
  input.readPixels(window.min.y, window.max.y);
  return passes;
}

const std::vector<std::string> kCyclesChannels = {
    "ViewLayer.Position.X", "ViewLayer.Position.Y", "ViewLayer.Position.Z", "ViewLayer.Normal.X",
    "ViewLayer.Normal.Y",   "ViewLayer.Normal.Z",   "ViewLayer.Depth.Z",    "ViewLayer.IndexMA.X",
    "ViewLayer.DiffCol.R",  "ViewLayer.DiffCol.G",  "ViewLayer.DiffCol.B",  "ViewLayer.GlossCol.R",
    "ViewLayer.Combined.A"};

Scene fixture_scene() { return load_scene(kFixtures / "scene.json"); }

glm::dvec3 forward_of(const Camera& c) { return glm::normalize(c.look_at - c.eye); }

// A pixel whose centre sample and whose 8 neighbours' centre samples hit a surface: nothing of the
// sky is inside its 1.5-pixel filter, so its filtered passes are the surface's own.
bool fully_covered(const Passes& p, const std::string& depth, int x, int y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = std::clamp(x + dx, 0, p.width - 1), ny = std::clamp(y + dy, 0, p.height - 1);
      if (!(p.at(depth, nx, ny) < 65504.0f)) return false;
    }
  return true;
}

// Every centre sample of the 3x3 neighbourhood on the same material: the filtered colour passes
// hold that material's colours alone.
bool one_material(const Passes& p, const std::string& material, int x, int y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = std::clamp(x + dx, 0, p.width - 1), ny = std::clamp(y + dy, 0, p.height - 1);
      if (p.at(material, nx, ny) != p.at(material, x, y)) return false;
    }
  return true;
}

// --- depth ---------------------------------------------------------------------------------------

TEST(BlenderDepth, CyclesDepthIsViewSpaceZ) {
  const Scene scene = fixture_scene();
  const Passes p = read_passes(kFixtures / "cycles.exr", kCyclesChannels);
  const glm::dvec3 eye = scene.camera.eye, forward = forward_of(scene.camera);
  double worst_view_z = 0.0, worst_distance = 0.0;
  int surfaces = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const double depth = p.at("ViewLayer.Depth.Z", x, y);
      if (depth >= 65504.0) continue;
      ++surfaces;
      const glm::dvec3 to_p = p.vec("ViewLayer.Position", x, y) - eye;
      worst_view_z = std::max(worst_view_z, std::abs(glm::dot(to_p, forward) - depth) / depth);
      worst_distance = std::max(worst_distance, std::abs(glm::length(to_p) - depth) / depth);
    }
  ASSERT_GT(surfaces, p.width * p.height / 2);
  // Float positions and depths about 8 m away: a few ulp of each; the exported camera rounds to 1e-7.
  EXPECT_LE(worst_view_z, 2e-6) << "Depth against dot(P - eye, forward)";
  EXPECT_GE(worst_distance, 0.05) << "Depth against |P - eye| should be far off towards the corners";
}

// EEVEE writes no position: rebuilt from its depth by the default convention, P is where Cycles
// saw the same pixel. EEVEE's depth is stored at half precision (8.1719 for Cycles' 8.1753), so
// positions agree to 2^-10 of the depth; the wrong convention is off by far more off-axis.
TEST(BlenderDepth, EeveeDepthOnlyRebuildsCyclesPositionsByDefault) {
  const Passes cycles = read_passes(kFixtures / "cycles.exr", kCyclesChannels);
  for (const char* convention : {"auto", "distance"}) {
    SCOPED_TRACE(convention);
    TempDir dir;
    const auto out = dir / "lit.exr";
    const auto run = run_phongcl("shade --scene tests/fixtures/blender/scene.json --gbuffer tests/fixtures/blender/eevee.exr"
                                 " --out " + out.string() + " --depth-convention " + convention);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    if (std::string(convention) == "auto") {
      EXPECT_NE(run.out.find("depth = view-space z (Blender's Depth pass is view-space z; --depth-convention overrides)"),
                std::string::npos) << run.out;
    }
  }
  ReadOptions options;
  GBufferRead read = read_gbuffer(kFixtures / "eevee.exr", options);
  ASSERT_TRUE(read.needs_positions_from_depth());
  EXPECT_EQ(read.depth_convention, DepthConvention::view_z);
  options.depth_convention = DepthConvention::distance;
  EXPECT_EQ(read_gbuffer(kFixtures / "eevee.exr", options).depth_convention, DepthConvention::distance);

  // Rebuild here, with this test's own rays, under both conventions.
  const Scene scene = fixture_scene();
  const Camera& c = scene.camera;
  const glm::dvec3 forward = forward_of(c), right = glm::normalize(glm::cross(forward, c.up)),
                   up = glm::cross(right, forward);
  const double half_h = std::tan(glm::radians(c.fov_y_deg) / 2), half_w = half_h * c.width / c.height;
  const Passes eevee = read_passes(kFixtures / "eevee.exr", {"ViewLayer.Depth.Z"});
  double worst_view_z = 0.0, worst_distance = 0.0;
  for (int y = 1; y + 1 < eevee.height; ++y)
    for (int x = 1; x + 1 < eevee.width; ++x) {
      if (!fully_covered(cycles, "ViewLayer.Depth.Z", x, y) || !fully_covered(eevee, "ViewLayer.Depth.Z", x, y)) continue;
      const double sx = (x + 0.5) / c.width * 2 - 1, sy = 1 - (y + 0.5) / c.height * 2;
      const glm::dvec3 ray = forward + sx * half_w * right + sy * half_h * up;
      const double depth = eevee.at("ViewLayer.Depth.Z", x, y);
      const glm::dvec3 truth = cycles.vec("ViewLayer.Position", x, y);
      const double tolerance = std::ldexp(depth, -10);
      worst_view_z = std::max(worst_view_z, glm::length(c.eye + depth / glm::dot(ray, forward) * ray - truth) / tolerance);
      worst_distance = std::max(worst_distance, glm::length(c.eye + depth * glm::normalize(ray) - truth) / tolerance);
    }
  EXPECT_LE(worst_view_z, 1.0) << "in units of 2^-10 of the depth";
  EXPECT_GE(worst_distance, 10.0);
}

// --- layouts -------------------------------------------------------------------------------------

TEST(BlenderLayouts, FileOutputNodeIsBlenderWithoutALayer) {
  const GBufferRead file_output = read_gbuffer(kFixtures / "file_output.exr", {});
  EXPECT_EQ(file_output.layout, Layout::blender);
  EXPECT_EQ(file_output.description.rfind("blender (File Output node: Position, Normal, Depth, DiffCol, IndexMA, Alpha; "
                                          "kd from DiffCol, ks from the scene's table; GlossCol not used as ks",
                                          0),
            0u)
      << file_output.description;
  // The same render's passes as the multilayer file holds them.
  const GBufferRead multilayer = read_gbuffer(kFixtures / "cycles.exr", {});
  const GBuffer &a = file_output.gbuffer, &b = multilayer.gbuffer;
  ASSERT_EQ(a.pixel_count(), b.pixel_count());
  for (std::size_t i = 0; i < a.pixel_count(); ++i) {
    ASSERT_EQ(a.material[i], b.material[i]) << "pixel " << i;
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(a.position[c][i], b.position[c][i]) << "pixel " << i;
      ASSERT_EQ(a.normal[c][i], b.normal[c][i]) << "pixel " << i;
      ASSERT_EQ(a.kd[c][i], b.kd[c][i]) << "pixel " << i;
    }
  }
}

// The renderer's own image rides along only when asked for: the view layer's Combined (the
// multilayer Cycles file also holds the compositor's Composite.Combined, here a copy of it), a File
// Output node's Image; every fixture has one, and the shading passes are the same either way.
TEST(BlenderBeauty, CombinedIsReadOnlyWhenAskedAndIsTheLayersOwn) {
  ReadOptions with_beauty;
  with_beauty.beauty = true;
  const struct {
    const char* file;
    const char* label;
    std::string channel;  // prefix of the R, G, B channels
  } cases[] = {{"cycles.exr", "Combined", "ViewLayer.Combined."}, {"eevee.exr", "Combined", "ViewLayer.Combined."},
               {"transparent.exr", "Combined", "ViewLayer.Combined."}, {"file_output.exr", "Image", "Image."}};
  for (const auto& c : cases) {
    const GBufferRead plain = read_gbuffer(kFixtures / c.file, {});
    EXPECT_FALSE(plain.gbuffer.has_beauty()) << c.file;
    EXPECT_EQ(plain.beauty, "") << c.file;
    const GBufferRead read = read_gbuffer(kFixtures / c.file, with_beauty);
    ASSERT_TRUE(read.gbuffer.has_beauty()) << c.file;
    EXPECT_EQ(read.beauty, c.label) << c.file;
    EXPECT_EQ(read.description, plain.description) << c.file;
    EXPECT_EQ(read.gbuffer.material, plain.gbuffer.material) << c.file;
    const Passes p = read_passes(kFixtures / c.file, {c.channel + "R", c.channel + "G", c.channel + "B"});
    double lit = 0.0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const float expected = p.at(c.channel + "RGB"[ch], x, y);
          ASSERT_EQ(read.gbuffer.beauty[ch][std::size_t(y) * p.width + x], expected) << c.file << " at " << x << ", " << y;
          lit += expected;
        }
    EXPECT_GT(lit, 0.0) << c.file << ": the render is not black";
  }
}

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

TEST(BlenderLayouts, KdFromDiffColKsFromTheTable) {
  const Scene scene = fixture_scene();
  const Passes p = read_passes(kFixtures / "cycles.exr", kCyclesChannels);
  const Passes eevee = read_passes(kFixtures / "eevee.exr", {"ViewLayer.GlossCol.R", "ViewLayer.Depth.Z"});
  const GBuffer g = read_gbuffer(kFixtures / "cycles.exr", {}).gbuffer;
  EXPECT_FALSE(g.has_per_pixel_ks());
  ASSERT_TRUE(g.has_per_pixel_kd());
  double cycles_gloss = 1.0, eevee_gloss = 0.0;
  int checked = 0, base_colour = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      if (!fully_covered(p, "ViewLayer.Depth.Z", x, y) || !one_material(p, "ViewLayer.IndexMA.X", x, y)) continue;
      const std::size_t i = std::size_t(y) * p.width + x;
      const Material& m = scene.materials.at(static_cast<std::size_t>(p.at("ViewLayer.IndexMA.X", x, y)));
      ++checked;
      bool same = true;
      for (int c = 0; c < 3; ++c) same &= std::abs(g.kd[c][i] - m.kd[c]) <= 1e-6;
      base_colour += same;
      cycles_gloss = std::min<double>(cycles_gloss, p.at("ViewLayer.GlossCol.R", x, y));
      if (fully_covered(eevee, "ViewLayer.Depth.Z", x, y))
        eevee_gloss = std::max<double>(eevee_gloss, eevee.at("ViewLayer.GlossCol.R", x, y));
    }
  // DiffCol is the base colour, but for the odd pixel where a sliver of another material falls
  // between the centre samples inside the filter's footprint (2 of 1,200 here).
  EXPECT_GE(base_colour, checked * 99 / 100) << base_colour << " of " << checked;
  // Why GlossCol is not ks by default: 1 on every Cycles surface, a few per cent in EEVEE.
  EXPECT_GE(cycles_gloss, 0.999);
  EXPECT_LE(eevee_gloss, 0.2);
  ReadOptions asked;
  asked.ks = ColourSource::pass;
  EXPECT_TRUE(read_gbuffer(kFixtures / "cycles.exr", asked).gbuffer.has_per_pixel_ks());
}

TEST(BlenderLayouts, EveryPixelMaterialZeroIsWarned) {
  const GBufferRead unset = read_gbuffer(kFixtures / "transparent.exr", {});
  ASSERT_EQ(unset.warnings.size(), 1u);
  EXPECT_NE(unset.warnings[0].find("every surface pixel has material index 0"), std::string::npos) << unset.warnings[0];
  EXPECT_TRUE(read_gbuffer(kFixtures / "cycles.exr", {}).warnings.empty());
  EXPECT_TRUE(read_gbuffer(kFixtures / "eevee.exr", {}).warnings.empty()) << "no material pass: described, not warned";
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

// --- shading -------------------------------------------------------------------------------------

// The Phong formula evaluated straight from a file's passes (kd from DiffCol, the rest from the
// table by IndexMA), for fully covered pixels.
glm::dvec3 shade_from_passes(const Scene& scene, const Passes& p, const std::string& prefix, const char* material,
                             const glm::dvec3& position, int x, int y) {
  const auto index = material ? static_cast<std::size_t>(p.at(material, x, y)) : 0;
  const Material& m = scene.materials.at(index);
  SurfacePoint s;
  s.position = position;
  s.normal = p.vec(prefix + "Normal", x, y);
  s.ka = m.ka;
  s.kd = p.vec(prefix + "DiffCol", x, y, "RGB");
  s.ks = m.ks;
  s.shininess = m.shininess;
  return reference_shade_point(scene, s).total();
}

// Every fixture shades with only --scene and --gbuffer: announced as Blender, within 1e-4 of the
// formula from the passes on every fully covered pixel, and alpha = coverage elsewhere.
TEST(BlenderShading, EveryFixtureShadesWithNoFlags) {
  const Scene scene = fixture_scene();
  const Camera& c = scene.camera;
  struct Case {
    const char* file;
    std::string prefix, depth, material;
    const char* announced;
  };
  const std::vector<Case> cases = {
      {"cycles.exr", "ViewLayer.", "ViewLayer.Depth.Z", "ViewLayer.IndexMA.X", "layout     blender (view layer 'ViewLayer'"},
      {"file_output.exr", "", "Depth.V", "IndexMA.V", "layout     blender (File Output node"},
      {"eevee.exr", "ViewLayer.", "ViewLayer.Depth.Z", "", "depth = view-space z"},
      {"transparent.exr", "ViewLayer.", "ViewLayer.Depth.Z", "ViewLayer.IndexMA.X", "coverage from alpha"},
  };
  const glm::dvec3 forward = forward_of(c), right = glm::normalize(glm::cross(forward, c.up)), up = glm::cross(right, forward);
  const double half_h = std::tan(glm::radians(c.fov_y_deg) / 2), half_w = half_h * c.width / c.height;
  for (const Case& k : cases) {
    SCOPED_TRACE(k.file);
    TempDir dir;
    const auto out = dir / "lit.exr";
    const auto run = run_phongcl("shade --scene tests/fixtures/blender/scene.json --gbuffer tests/fixtures/blender/" +
                                 std::string(k.file) + " --out " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find(k.announced), std::string::npos) << run.out;
    const Image lit = read_exr(out);

    std::vector<std::string> names = {k.depth};
    for (const char* n : {"Normal.X", "Normal.Y", "Normal.Z", "DiffCol.R", "DiffCol.G", "DiffCol.B"}) names.push_back(k.prefix + n);
    const bool has_position = k.file != std::string("eevee.exr");
    if (has_position)
      for (const char* n : {"Position.X", "Position.Y", "Position.Z"}) names.push_back(k.prefix + n);
    if (!k.material.empty()) names.push_back(k.material);
    const bool transparent = k.file == std::string("transparent.exr");
    if (transparent) names.push_back("ViewLayer.Combined.A");
    const Passes p = read_passes(kFixtures / k.file, names);

    double worst = 0.0;
    int checked = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const float* pixel = lit.pixel(std::size_t(y) * p.width + x);
        if (!(p.at(k.depth, x, y) < 65504.0f)) {
          EXPECT_EQ(pixel[3], 0.0f) << "an opaque pixel whose centre sample missed, at " << x << "," << y;
          continue;
        }
        if (!fully_covered(p, k.depth, x, y) || (transparent && p.at("ViewLayer.Combined.A", x, y) != 1.0f)) continue;
        // Between two surfaces (a normal averaged over directions 16 degrees or more apart) the
        // edge policy takes the centre surface's normal from a neighbour: not straight from the pass.
        if (glm::length(p.vec(k.prefix + "Normal", x, y)) < 0.98) continue;
        glm::dvec3 position;
        if (has_position) {
          position = p.vec(k.prefix + "Position", x, y);
        } else {
          const double sx = (x + 0.5) / c.width * 2 - 1, sy = 1 - (y + 0.5) / c.height * 2;
          const glm::dvec3 ray = forward + sx * half_w * right + sy * half_h * up;
          position = c.eye + double(p.at(k.depth, x, y)) / glm::dot(ray, forward) * ray;
        }
        const glm::dvec3 expected =
            shade_from_passes(scene, p, k.prefix, k.material.empty() ? nullptr : k.material.c_str(), position, x, y);
        ++checked;
        EXPECT_EQ(pixel[3], 1.0f) << x << "," << y;
        for (int ch = 0; ch < 3; ++ch)
          worst = std::max(worst, std::abs(pixel[ch] - expected[ch]) / std::max(std::abs(expected[ch]), 1e-3));
      }
    EXPECT_GT(checked, p.width * p.height / 3);
    // The kernel holds 5e-4 of the double reference in general and a few 1e-6 on scenes like this.
    EXPECT_LE(worst, 1e-4) << "worst relative error over " << checked << " fully covered pixels";
  }
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

// The issue's measure: against the 4x4-supersampled render with the filter off (every sub-sample
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
      for (int c = 0; c < 4; ++c)
        // 5e-4 relative: the kernel's bound against the reference (docs/shading.md "Accuracy").
        ASSERT_NEAR(lit.pixel(i)[c], expected.pixel(i)[c], 5e-4 * std::max(1.0f, std::abs(expected.pixel(i)[c])))
            << "pixel " << i << " channel " << c;
    }
    EXPECT_GT(partial, 10);
  }
}

// --- cameras from the file's header ----------------------------------------------------------------

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
