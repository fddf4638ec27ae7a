// The C++ peers of the throughput benchmark against the double reference, their float exp/log,
// and the sweep helpers (generated lights, resampling, row sampling).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/error.h"
#include "peers/float_math.h"
#include "peers/light_sweep.h"
#include "peers/many_lights.h"
#include "peers/peers.h"
#include "shading_support.h"

namespace phongcl {
namespace {

using testing::kRelativeBound;
using testing::random_scene;
using testing::RandomSceneSpec;
using testing::shading_error;

using PeerFunction = void (*)(const PackedFrame&, const PackedScene&, float*);
struct Peer {
  const char* name;
  PeerFunction shade;
};
const Peer kPeers[] = {{"cpp-scalar", shade_scalar}, {"cpp-simd", shade_simd}};

Image shade_with(const Peer& peer, const Scene& scene, const GBuffer& gbuffer) {
  Image image = image_like(gbuffer);
  peer.shade(pack_frame(gbuffer, scene), pack_scene(scene), image.rgba.data());
  return image;
}

void expect_matches_reference(const Scene& scene, const GBuffer& gbuffer, const std::string& what) {
  const Image reference = reference_image(scene, gbuffer);
  for (const Peer& peer : kPeers) {
    const Image image = shade_with(peer, scene, gbuffer);
    const ErrorStats stats = shading_error(image, reference, testing::shaded_mask(gbuffer));
    EXPECT_LE(stats.max_rel, kRelativeBound) << peer.name << " on " << what << ": " << testing::describe_worst(stats);
    EXPECT_EQ(stats.nonfinite_mismatches, 0u) << peer.name << " on " << what;
    testing::expect_background_exact(image, scene, gbuffer);
  }
}

TEST(Peers, MatchReferenceOnRandomScenesWithZeroToSixteenLights) {
  unsigned seed = 6502;
  for (int points : {0, 1, 3, 8}) {
    for (int directionals : {0, 1, 8}) {
      RandomSceneSpec spec;
      spec.point_lights = points;
      spec.directional_lights = directionals;
      const auto [scene, gbuffer] = random_scene(spec, ++seed);
      expect_matches_reference(scene, gbuffer, std::to_string(points) + " point + " + std::to_string(directionals) +
                                                   " directional, seed " + std::to_string(seed));
    }
  }
}

TEST(Peers, MatchReferenceOnSizesThatNoBlockDivides) {
  for (auto [width, height] : {std::pair{1, 1}, {15, 1}, {17, 3}, {37, 23}, {64, 2}}) {
    RandomSceneSpec spec;
    spec.width = width;
    spec.height = height;
    const auto [scene, gbuffer] = random_scene(spec, 17u + width);
    expect_matches_reference(scene, gbuffer, std::to_string(width) + "x" + std::to_string(height));
  }
}

// cpp-tiled (tile boxes, culling through coarse boxes of tiles, each tile row's light loop
// vectorised and skipping the lights out of the row's reach) against the reference, with 400 ranged
// point and spot lights of which a pixel is reached by about 6, on a frame that the tiles do not
// divide, at its default schedule and at the extremes of bench --peer-schedules' grid; and culled to
// a fraction of the pairs.
TEST(Peers, TiledPeerMatchesReferenceWithManyRangedLights) {
  Scene scene = load_scene(std::filesystem::path(PHONGCL_SOURCE_DIR) / "scenes/default/scene.json");
  scene.camera.width = 200;
  scene.camera.height = 130;
  const GBuffer gbuffer = generate_gbuffer(scene);
  const Scene lit = with_many_lights(scene, gbuffer, 400, 6.0);
  const Image reference = reference_image(lit, gbuffer);
  const std::vector<bool> mask = testing::shaded_mask(gbuffer);
  const auto shaded = static_cast<double>(std::count(mask.begin(), mask.end(), true));
  for (TiledPeerSchedule schedule : {TiledPeerSchedule{}, TiledPeerSchedule{8, 4, 1}, TiledPeerSchedule{32, 16, 16}}) {
    SCOPED_TRACE(describe(schedule));
    Image image = image_like(gbuffer);
    const TiledPeerStats stats =
        shade_tiled(pack_frame(gbuffer, lit), pack_scene(lit), gbuffer.width, gbuffer.height, schedule, image.rgba.data());
    const ErrorStats error = shading_error(image, reference, mask);
    EXPECT_LE(error.max_rel, kRelativeBound) << testing::describe_worst(error);
    EXPECT_EQ(error.nonfinite_mismatches, 0u);
    testing::expect_background_exact(image, lit, gbuffer);
    EXPECT_LT(stats.kept_pairs, 0.2 * shaded * 400) << "the lists keep a few of the 400 lights";
    EXPECT_GE(stats.kept_pairs, mean_lights_reaching(lit, gbuffer) * shaded) << "every light that reaches a pixel";
  }
}

TEST(Peers, ShininessZeroGivesFullHighlightEvenFacingAway) {
  RandomSceneSpec spec;
  auto [scene, gbuffer] = random_scene(spec, 99);
  for (Material& material : scene.materials) material.shininess = 0.0;  // pow(0, 0) = 1 where v.r <= 0
  expect_matches_reference(scene, gbuffer, "q = 0");
}

TEST(Peers, ZeroAndExtremeNormalsFollowTheDegeneratePolicy) {
  RandomSceneSpec spec;
  auto [scene, gbuffer] = random_scene(spec, 7);
  for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) {
    const float scale = i % 3 == 0 ? 0.0f : i % 3 == 1 ? 1e30f : 1e-30f;  // zero stays zero; huge and tiny are directions
    for (auto& plane : gbuffer.normal) plane[i] *= scale;
  }
  expect_matches_reference(scene, gbuffer, "zero, 1e30 and 1e-30 normals");
}

TEST(Peers, PerPixelMaterialChannelsAreRefused) {
  RandomSceneSpec spec;
  spec.per_pixel_materials = true;
  const auto [scene, gbuffer] = random_scene(spec, 3);
  EXPECT_THROW(pack_frame(gbuffer, scene), InputError);
}

TEST(PeerMath, LogAndExpAreAccurateToAFewUlps) {
  for (double x = 1e-44; x < 2.0; x *= 1.0137) {
    const float xf = static_cast<float>(x);
    const double exact = std::log(static_cast<double>(xf));
    const float one_minus = static_cast<float>(1.0 - static_cast<double>(xf));
    const double got = peer_math::log_positive(xf, one_minus);
    EXPECT_LE(std::abs(got - exact), 3e-7 * std::max(std::abs(exact), 1e-3)) << "ln(" << xf << ")";
  }
  // Near 1 the argument's own rounding is what the caller's 1 - x avoids: exact from the small m.
  for (double m = 1e-9; m < 0.29; m *= 1.5) {
    const double got = peer_math::log_positive(static_cast<float>(1.0 - m), static_cast<float>(m));
    EXPECT_LE(std::abs(got - std::log1p(-static_cast<double>(static_cast<float>(m)))), 3e-7 * m) << "ln(1 - " << m << ")";
  }
  for (double y = -87.3; y < 80.0; y += 0.173) {
    const double exact = std::exp(static_cast<double>(static_cast<float>(y)));
    const double got = peer_math::exp_float(static_cast<float>(y));
    EXPECT_LE(std::abs(got - exact), 4e-7 * exact) << "exp(" << y << ")";
  }
  // Below 2^-126 (float's smallest normal) the result is 0, as in the kernel: no subnormals.
  EXPECT_EQ(peer_math::exp_float(-87.34f), 0.0f);
  EXPECT_EQ(peer_math::exp_float(-200.0f), 0.0f);
}

TEST(LightSweep, GeneratedLightsAreHalfPointHalfDirectionalAndDeterministic) {
  Scene scene;
  scene.camera.eye = {0, 2, 10};
  scene.camera.look_at = {0, 0, 0};
  EXPECT_THROW(with_generated_lights(scene, -1), std::invalid_argument);
  for (int count : {0, 1, 2, 5, 16, 256}) {
    const Scene lit = with_generated_lights(scene, count);
    ASSERT_EQ(static_cast<int>(lit.lights.size()), count);
    int points = 0;
    glm::dvec3 total(0.0);
    for (const Light& light : lit.lights) {
      total += light.color;
      if (light.type == LightType::point) {
        ++points;
        EXPECT_GT(light.position.y, 0.0) << "point lights hang above look_at";
      } else {
        EXPECT_LT(light.direction.y, 0.0) << "directional lights shine down";
      }
    }
    EXPECT_EQ(points, (count + 1) / 2);
    if (count > 0) {
      EXPECT_NEAR(total.r + total.g + total.b, 3 * 2.0 * 0.6, 0.7) << "brightness independent of count";
    }
    const Scene again = with_generated_lights(scene, count);
    for (std::size_t k = 0; k < lit.lights.size(); ++k) {
      EXPECT_EQ(lit.lights[k].position, again.lights[k].position);
      EXPECT_EQ(lit.lights[k].direction, again.lights[k].direction);
      EXPECT_EQ(lit.lights[k].color, again.lights[k].color);
    }
  }
}

GBuffer numbered_gbuffer(int width, int height) {
  GBuffer g;
  g.width = width;
  g.height = height;
  const std::size_t n = g.pixel_count();
  for (auto* planes : {&g.position, &g.normal, &g.kd}) for (auto& plane : *planes) plane.resize(n);
  g.material.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) g.position[c][i] = g.normal[c][i] = g.kd[c][i] = static_cast<float>(i) + 0.1f * c;
    g.material[i] = i % 2 ? -1.0f : 0.0f;
  }
  return g;
}

TEST(LightSweep, NearestResampleCopiesTheSourcePixelUnderEachCentre) {
  const GBuffer source = numbered_gbuffer(4, 2);  // pixel i holds i
  const GBuffer half = resample_nearest(source, 2, 1);
  ASSERT_EQ(half.pixel_count(), 2u);
  // Target centres (0.5, 0.5) and (1.5, 0.5) scale to source (1, 1) and (3, 1): pixels 5 and 7.
  EXPECT_EQ(half.position[0][0], 5.0f);
  EXPECT_EQ(half.position[0][1], 7.0f);
  EXPECT_EQ(half.data_window.x_max, 1);
  const GBuffer doubled = resample_nearest(source, 8, 4);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 8; ++x) {
      const std::size_t from = static_cast<std::size_t>(y / 2) * 4 + x / 2;
      const std::size_t to = static_cast<std::size_t>(y) * 8 + x;
      EXPECT_EQ(doubled.position[2][to], source.position[2][from]);
      EXPECT_EQ(doubled.normal[1][to], source.normal[1][from]);
      EXPECT_EQ(doubled.kd[0][to], source.kd[0][from]);
      EXPECT_EQ(doubled.material[to], source.material[from]) << "background stays background";
    }
  }
  EXPECT_FALSE(doubled.has_per_pixel_ks()) << "absent channels stay absent";
  EXPECT_THROW(resample_nearest(source, 0, 3), std::invalid_argument);
}

TEST(LightSweep, EveryNthRowTakesRowsZeroStepTwoStep) {
  const GBuffer source = numbered_gbuffer(3, 7);
  const GBuffer rows = every_nth_row(source, 3);  // rows 0, 3, 6
  ASSERT_EQ(rows.height, 3);
  EXPECT_EQ(rows.material.size(), 9u);
  EXPECT_EQ(rows.position[0][3], source.position[0][9]);
  EXPECT_EQ(rows.kd[1][8], source.kd[1][20]);
  Image image(3, 7);
  for (std::size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<float>(i);
  const Image image_rows = every_nth_row(image, 3);
  ASSERT_EQ(image_rows.height, 3);
  EXPECT_EQ(image_rows.pixel(4)[2], image.pixel(10)[2]);
  EXPECT_THROW(every_nth_row(source, 0), std::invalid_argument);
}

}  // namespace
}  // namespace phongcl
