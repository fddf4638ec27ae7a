// make_gbuffer: the caller's planes, interleaved arrays and padded rows become the same planes.
#include <gtest/gtest.h>

#include <phongcl/gbuffer_view.hpp>

#include <stdexcept>
#include <vector>

namespace phongcl {
namespace {

constexpr int kWidth = 5, kHeight = 3;

// A distinct value per pixel and channel, so a wrong stride or offset shows.
float value(int x, int y, int c) { return static_cast<float>(100 * y + 10 * x + c); }

TEST(GBufferView, InterleavedPlanarAndPaddedRowsGiveTheSamePlanes) {
  std::vector<float> interleaved(3 * kWidth * kHeight), material(kWidth * kHeight);
  std::vector<float> planes[3];
  constexpr int kPaddedRow = 8;  // floats per row of a padded single-channel image
  std::vector<float> padded_alpha(kPaddedRow * kHeight, -7.0f);
  for (auto& plane : planes) plane.resize(kWidth * kHeight);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const int i = y * kWidth + x;
      for (int c = 0; c < 3; ++c) interleaved[3 * i + c] = planes[c][i] = value(x, y, c);
      material[i] = static_cast<float>(i % 2);
      padded_alpha[y * kPaddedRow + x] = x == 2 ? 0.0f : 1.0f;
    }

  GBufferView view;
  view.width = kWidth;
  view.height = kHeight;
  view.position = interleaved3(interleaved.data());
  view.normal = planar3(planes[0].data(), planes[1].data(), planes[2].data());
  view.material = {material.data()};
  view.alpha = {padded_alpha.data(), 1, kPaddedRow};
  const GBuffer g = make_gbuffer(view);

  ASSERT_EQ(g.width, kWidth);
  ASSERT_EQ(g.height, kHeight);
  EXPECT_FALSE(g.has_per_pixel_kd());
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const int i = y * kWidth + x;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(g.position[c][i], value(x, y, c)) << "P at (" << x << ", " << y << ") channel " << c;
        EXPECT_EQ(g.normal[c][i], value(x, y, c)) << "N at (" << x << ", " << y << ") channel " << c;
      }
      // alpha 0 marks background; elsewhere the index is kept.
      EXPECT_EQ(g.material[i], x == 2 ? -1.0f : static_cast<float>(i % 2)) << "material at (" << x << ", " << y << ")";
    }
}

TEST(GBufferView, MissingOrPartialChannelsAreErrors) {
  std::vector<float> data(3 * kWidth * kHeight, 1.0f);
  GBufferView view;
  view.width = kWidth;
  view.height = kHeight;
  view.position = view.normal = interleaved3(data.data());
  EXPECT_THROW(make_gbuffer(view), std::invalid_argument);  // no material
  view.material = {data.data(), 3};
  EXPECT_NO_THROW(make_gbuffer(view));
  view.kd = {{data.data(), 3}, {}, {}};
  EXPECT_THROW(make_gbuffer(view), std::invalid_argument);  // kd with one channel of three
  view.kd = {};
  view.height = 0;
  EXPECT_THROW(make_gbuffer(view), std::invalid_argument);
}

}  // namespace
}  // namespace phongcl
