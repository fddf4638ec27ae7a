// report/light_agreement.h: which pixels count (away from silhouettes and the sky) and when a light
// agrees (within the tolerance times its unshadowed value), and the relative errors' median and 99th
// percentile over the lit pixels.
#include <cmath>

#include <gtest/gtest.h>

#include "report/light_agreement.h"

namespace phongcl {
namespace {

constexpr int kWidth = 6, kHeight = 5;

// Object 1 on the left three columns, object 2 on the right three; the sky at (5, 4).
std::vector<bool> two_objects_mask() {
  std::vector<float> object(kWidth * kHeight), depth(kWidth * kHeight, 3.0f);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) object[y * kWidth + x] = x < 3 ? 1.0f : 2.0f;
  depth[4 * kWidth + 5] = 1e10f;
  return away_from_silhouettes(object, depth, kWidth, kHeight);
}

TEST(LightAgreement, PixelsNextToAnotherObjectTheSkyOrTheBorderAreLeftOut) {
  const std::vector<bool> mask = two_objects_mask();
  // Only x = 1 and x = 4 in rows 1 to 3 have a 3x3 of one object; (4, 3) touches the sky.
  std::vector<bool> expected(kWidth * kHeight, false);
  for (int y = 1; y <= 3; ++y) expected[y * kWidth + 1] = expected[y * kWidth + 4] = true;
  expected[3 * kWidth + 4] = false;
  EXPECT_EQ(mask, expected);
}

TEST(LightAgreement, WithinTheToleranceOfTheUnshadowedValueEveryLight) {
  const std::vector<bool> mask(kWidth * kHeight, true);
  LightImages first, second;
  for (LightImages* light : {&first, &second})
    for (int c = 0; c < 3; ++c) {
      light->expected[c].assign(mask.size(), 1.0f);
      light->shaded[c].assign(mask.size(), 1.0f);
      light->unshadowed[c].assign(mask.size(), 2.0f);
    }
  first.shaded[1][3] = 1.099f;  // 0.099 off: within 5% of 2
  first.shaded[2][4] = 1.101f;  // just beyond
  second.shaded[0][4] = 0.0f;   // a shadow Cycles does not have
  second.shaded[0][7] = 0.0f;
  const LightAgreement agreement = light_agreement({first, second}, mask, kWidth, 0.05);
  EXPECT_EQ(agreement.pixels, mask.size());
  EXPECT_EQ(agreement.agreeing_per_light, (std::vector<std::size_t>{mask.size() - 1, mask.size() - 2}));
  EXPECT_EQ(agreement.agreeing, mask.size() - 2);  // pixels 4 and 7
  EXPECT_EQ(agreement.worst_x, 4);
  EXPECT_EQ(agreement.worst_y, 0);
  EXPECT_NEAR(agreement.worst_miss, 10.0, 1e-6);  // a miss of 1 against an allowance of 0.1
}

// 30 pixels: 20 lit at 1 with errors 0, 1e-4 ... 1.9e-3 (one channel each), 8 dim ones below the floor
// that are far off, and two NaNs: the median and 99th percentile are of the 22 lit pixels, a NaN
// counted as infinitely far.
TEST(LightAgreement, RelativeErrorsOverTheLitPixels) {
  const std::vector<bool> mask(kWidth * kHeight, true);
  LightImages light;
  for (int c = 0; c < 3; ++c) {
    light.expected[c].assign(mask.size(), 1.0f);
    light.shaded[c].assign(mask.size(), 1.0f);
  }
  for (int i = 0; i < 20; ++i) light.shaded[i % 3][i] = 1.0f + 1e-4f * static_cast<float>(i);
  for (int i = 20; i < 28; ++i)
    for (int c = 0; c < 3; ++c) {
      light.expected[c][i] = 1e-4f;
      light.shaded[c][i] = 1.0f;
    }
  light.shaded[0][28] = light.shaded[1][29] = NAN;
  const RelativeErrors errors = relative_errors(light, mask, 1e-3);
  EXPECT_EQ(errors.pixels, 22u);
  EXPECT_NEAR(errors.median, 1e-3, 1e-7);  // index 0.5 * 21, rounded down: the 11th smallest
  EXPECT_TRUE(std::isinf(errors.p99)) << errors.p99;  // index 20 of 0 to 21: a NaN
  light.shaded[0][28] = light.shaded[1][29] = 1.0f;
  const RelativeErrors fixed = relative_errors(light, mask, 1e-3);
  EXPECT_NEAR(fixed.median, 8e-4, 1e-7);
  EXPECT_NEAR(fixed.p99, 1.8e-3, 1e-7);
}

}  // namespace
}  // namespace phongcl
