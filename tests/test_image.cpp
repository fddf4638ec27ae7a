// Images: EXR round trips, PNG display encoding and the error metrics.
#include <gtest/gtest.h>
#include <png.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.h"
#include "image/image.h"
#include "renderer_files.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;
using testing::decode_with_openexr;
using testing::TempDir;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

std::string contents(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Distinct values per channel and pixel, not representable in half.
Image ramp(int width, int height) {
  Image image(width, height);
  for (std::size_t i = 0; i < image.pixel_count(); ++i)
    for (int c = 0; c < 4; ++c) image.pixel(i)[c] = 0.01f * static_cast<float>(i) + 0.1f * c + 1.0f / 3.0f;
  return image;
}

TEST(ImageLike, TakesSizeAndWindowsFromTheGBuffer) {
  GBuffer g;
  g.width = 4, g.height = 3;
  g.data_window = {5, 7, 8, 9};
  g.display_window = {0, 0, 99, 49};
  const Image image = image_like(g);
  EXPECT_EQ(image.width, 4);
  EXPECT_EQ(image.height, 3);
  EXPECT_EQ(image.data_window.x_min, 5);
  EXPECT_EQ(image.data_window.y_max, 9);
  EXPECT_EQ(image.display_window.x_max, 99);
  ASSERT_EQ(image.rgba.size(), 4u * 12u);
  for (float v : image.rgba) EXPECT_EQ(v, 0.0f);
}

TEST(ExrImage, FloatRoundTripKeepsValuesAndWindows) {
  TempDir dir;
  Image written = ramp(7, 5);
  written.data_window = {-2, 10, 4, 14};
  written.display_window = {0, 0, 31, 31};
  write_exr(written, dir / "out.exr");
  const Image read = read_exr(dir / "out.exr");
  EXPECT_EQ(read.width, 7);
  EXPECT_EQ(read.height, 5);
  EXPECT_EQ(read.data_window, written.data_window);
  EXPECT_EQ(read.display_window, written.display_window);
  ASSERT_EQ(read.rgba.size(), written.rgba.size());
  // Float32 storage is lossless: any difference is a bug in the plumbing.
  for (std::size_t i = 0; i < written.rgba.size(); ++i) ASSERT_EQ(read.rgba[i], written.rgba[i]) << i;
}

TEST(ExrImage, HalfRoundTripWithinHalfPrecision) {
  TempDir dir;
  const Image written = ramp(6, 4);
  write_exr(written, dir / "out.exr", ExrPixelType::half);
  EXPECT_EQ(Imf::InputFile((dir / "out.exr").c_str()).header().channels().findChannel("A")->type, Imf::HALF);
  const Image read = read_exr(dir / "out.exr");
  ASSERT_EQ(read.rgba.size(), written.rgba.size());
  // Half keeps an 11-bit significand; round-to-nearest is within 2^-11 relative.
  for (std::size_t i = 0; i < written.rgba.size(); ++i)
    EXPECT_NEAR(read.rgba[i], written.rgba[i], std::abs(written.rgba[i]) * std::ldexp(1.0f, -11)) << i;
}

TEST(ExrImage, LayeredExrNamesEachLayersChannels) {
  TempDir dir;
  Image combined = ramp(5, 3), diffuse = ramp(5, 3);
  combined.data_window = diffuse.data_window = {2, 4, 6, 6};
  for (float& v : diffuse.rgba) v *= 2.0f;
  write_layered_exr({{"", &combined, true}, {"diffuse", &diffuse, false}}, dir / "layers.exr");
  Imf::InputFile in((dir / "layers.exr").c_str());
  std::vector<std::string> names;
  for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) names.emplace_back(it.name());
  EXPECT_EQ(names, (std::vector<std::string>{"A", "B", "G", "R", "diffuse.B", "diffuse.G", "diffuse.R"}));
  EXPECT_EQ(in.header().dataWindow().min.x, 2);

  const Plane green = decode_with_openexr(dir / "layers.exr", "diffuse.G");
  for (std::size_t i = 0; i < green.size(); ++i) ASSERT_EQ(green[i], diffuse.pixel(i)[1]) << i;
  // The unnamed layer is what read_exr (and compositors by default) see.
  EXPECT_EQ(read_exr(dir / "layers.exr").rgba, combined.rgba);

  // As half (`shade --aov --half`): every layer's channels, each value rounded to half's 11 bits.
  write_layered_exr({{"", &combined, true}, {"diffuse", &diffuse, false}}, dir / "half.exr", ExrPixelType::half);
  const Imf::InputFile half_file((dir / "half.exr").c_str());
  for (auto it = half_file.header().channels().begin(); it != half_file.header().channels().end(); ++it)
    EXPECT_EQ(it.channel().type, Imf::HALF) << it.name();
  const Plane green_half = decode_with_openexr(dir / "half.exr", "diffuse.G");
  for (std::size_t i = 0; i < green_half.size(); ++i)
    ASSERT_NEAR(green_half[i], diffuse.pixel(i)[1], 0x1p-11 * std::abs(diffuse.pixel(i)[1])) << i;
}

TEST(ExrImage, LayersOfDifferentSizesAreRejected) {
  TempDir dir;
  const Image combined = ramp(5, 3), other = ramp(4, 3);
  EXPECT_THROW(write_layered_exr({{"", &combined, true}, {"diffuse", &other, false}}, dir / "layers.exr"),
               std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir / "layers.exr"));
}

TEST(ExrImage, MissingAlphaReadsAsOpaque) {
  TempDir dir;
  const fs::path file = dir / "rgb.exr";
  const std::vector<float> rgb = {0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f};  // two pixels, interleaved
  Imf::Header header(2, 1);
  Imf::FrameBuffer frame_buffer;
  const char* names[] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    frame_buffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, header.dataWindow(), 3 * sizeof(float)));
  }
  {
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame_buffer);
    out.writePixels(1);
  }
  const Image read = read_exr(file);
  const std::vector<float> expected = {0.5f, 1.5f, 2.5f, 1.0f, 3.5f, 4.5f, 5.5f, 1.0f};
  EXPECT_EQ(read.rgba, expected);
}

TEST(ExrImage, MissingColorChannelIsNamed) {
  TempDir dir;
  const fs::path file = dir / "red.exr";
  const std::vector<float> red(4, 1.0f);
  Imf::Header header(2, 2);
  header.channels().insert("R", Imf::Channel(Imf::FLOAT));
  Imf::FrameBuffer frame_buffer;
  frame_buffer.insert("R", Imf::Slice::Make(Imf::FLOAT, red.data(), header.dataWindow()));
  {
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame_buffer);
    out.writePixels(2);
  }
  try {
    read_exr(file);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("red.exr: missing channel G"), std::string::npos) << e.what();
  }
}

TEST(ExrImage, BadFilesAreInputErrors) {
  TempDir dir;
  std::ofstream(dir / "text.exr") << "not an image\n";
  EXPECT_THROW(read_exr(dir / "text.exr"), InputError);
  EXPECT_THROW(read_exr(dir / "absent.exr"), InputError);
  write_exr(ramp(40, 40), dir / "cut.exr");
  fs::resize_file(dir / "cut.exr", fs::file_size(dir / "cut.exr") / 2);
  EXPECT_THROW(read_exr(dir / "cut.exr"), InputError);
}

TEST(ExrImage, WriteIntoMissingDirectoryLeavesNothing) {
  TempDir dir;
  EXPECT_THROW(write_exr(ramp(2, 2), dir / "missing" / "out.exr"), InputError);
  EXPECT_TRUE(fs::is_empty(dir.path));
}

// Reads a PNG back as 8-bit RGBA through libpng's simplified API.
std::vector<std::uint8_t> read_png(const fs::path& file, png_uint_32& width, png_uint_32& height) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, file.c_str())) throw std::runtime_error(png.message);
  png.format = PNG_FORMAT_RGBA;
  std::vector<std::uint8_t> bytes(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr)) throw std::runtime_error(png.message);
  width = png.width;
  height = png.height;
  return bytes;
}

struct DisplayCase {
  float value;
  DisplaySettings display;
  int expected_byte;
  const char* why;
};

TEST(PngImage, ToneMapsAndSrgbEncodingAtKnownPoints) {
  // Expected bytes from the formulas by hand, each at least 0.08 away from a rounding boundary.
  const DisplayCase cases[] = {
      {1.0f, {0.0, ToneMap::reinhard}, 188, "1/(1+1) = 0.5, sRGB 0.7354 (a 2.2 gamma would give 186)"},
      {3.0f, {0.0, ToneMap::reinhard}, 225, "0.75 -> sRGB 0.8808"},
      {0.5f, {1.0, ToneMap::reinhard}, 188, "one stop up makes it 1"},
      {0.2f, {0.0, ToneMap::clamp}, 124, "sRGB(0.2) = 0.4845"},
      {0.002f, {0.0, ToneMap::clamp}, 7, "linear segment: 12.92 * 0.002"},
      {2.0f, {0.0, ToneMap::clamp}, 255, "clamped to 1"},
      {1.0f, {0.0, ToneMap::aces}, 232, "2.54/3.16 = 0.8038 -> sRGB 0.9082"},
      {0.18f, {0.0, ToneMap::aces}, 141, "0.2669 -> sRGB 0.5535"},
      {-1.0f, {0.0, ToneMap::reinhard}, 0, "negative displays as black"},
      {kNaN, {0.0, ToneMap::aces}, 0, "NaN displays as black"},
      {kInf, {0.0, ToneMap::reinhard}, 255, "+Inf displays as white"},
      {kInf, {0.0, ToneMap::aces}, 255, "+Inf displays as white"},
  };
  TempDir dir;
  for (const auto& c : cases) {
    Image image(1, 1);
    for (int ch = 0; ch < 3; ++ch) image.pixel(0)[ch] = c.value;
    image.pixel(0)[3] = 1.0f;
    write_png(image, dir / "out.png", c.display);
    png_uint_32 width = 0, height = 0;
    const auto bytes = read_png(dir / "out.png", width, height);
    ASSERT_EQ(bytes.size(), 4u);
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_EQ(bytes[ch], c.expected_byte) << "value " << c.value << ": " << c.why;
  }
}

// display_rgba8 reads bytes from tables; the formula written out here is the oracle. Values on
// a geometric sweep over 2^-20..2^20, 1e-4 apart, so that every byte boundary of every curve is
// crossed with values on both sides close to it, at exposures that move the boundaries off the
// sweep's points; and each float next to a boundary the sweep found.
TEST(PngImage, DisplayTableEqualsTheFormulaEverywhere) {
  auto formula = [](float value, ToneMap map, double exposure) -> int {
    const double x = value * std::exp2(exposure);
    if (std::isnan(x) || x <= 0.0) return 0;
    if (std::isinf(x)) return 255;
    double t = map == ToneMap::clamp ? std::min(x, 1.0) : map == ToneMap::reinhard ? x / (1.0 + x)
             : std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    const double s = t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1.0 / 2.4) - 0.055;
    return static_cast<int>(std::lround(std::clamp(s, 0.0, 1.0) * 255.0));
  };
  std::vector<float> sweep;
  for (double x = std::exp2(-20.0); x < std::exp2(20.0); x *= 1.0001) sweep.push_back(static_cast<float>(x));
  for (const double exposure : {0.0, -3.7, 2.3, -40.0, 40.0}) {  // and the API's limits
    for (ToneMap map : {ToneMap::clamp, ToneMap::reinhard, ToneMap::aces}) {
      std::vector<float> values = sweep;
      for (std::size_t i = 1; i < sweep.size(); ++i)
        if (formula(sweep[i], map, exposure) != formula(sweep[i - 1], map, exposure))
          for (float v = sweep[i - 1]; v <= sweep[i] && values.size() < 2 * sweep.size(); v = std::nextafter(v, 2 * v))
            values.push_back(v);
      Image image(static_cast<int>(values.size()), 1);
      for (std::size_t i = 0; i < values.size(); ++i)
        for (int c = 0; c < 4; ++c) image.pixel(i)[c] = values[i];
      const std::vector<std::uint8_t> bytes = display_rgba8(image, {exposure, map});
      int mismatches = 0;
      for (std::size_t i = 0; i < values.size(); ++i)
        if (bytes[4 * i] != formula(values[i], map, exposure) && mismatches++ < 5)
          ADD_FAILURE() << "value " << values[i] << " curve " << static_cast<int>(map) << " exposure " << exposure
                        << ": table " << int(bytes[4 * i]) << ", formula " << formula(values[i], map, exposure);
      EXPECT_EQ(mismatches, 0);
    }
  }
}

TEST(PngImage, SizeRowOrderAndAlpha) {
  TempDir dir;
  Image image(3, 2);
  const float alphas[] = {0.5f, 2.0f, -1.0f, kNaN, 1.0f, 0.0f};
  for (std::size_t i = 0; i < image.pixel_count(); ++i) image.pixel(i)[3] = alphas[i];
  image.pixel(3)[0] = 1.0f;  // red marks the first pixel of the second row
  write_png(image, dir / "out.png", {0.0, ToneMap::clamp});
  EXPECT_EQ(contents(dir / "out.png").substr(1, 3), "PNG");
  EXPECT_NE(contents(dir / "out.png").find("sRGB"), std::string::npos) << "the sRGB chunk tags the encoding";
  png_uint_32 width = 0, height = 0;
  const auto bytes = read_png(dir / "out.png", width, height);
  EXPECT_EQ(width, 3u);
  EXPECT_EQ(height, 2u);
  const int expected_alpha[] = {128, 255, 0, 0, 255, 0};  // 127.5 rounds up; clamped; NaN -> 0
  for (int i = 0; i < 6; ++i) EXPECT_EQ(bytes[4 * i + 3], expected_alpha[i]) << "pixel " << i;
  EXPECT_EQ(bytes[4 * 3 + 0], 255);
  EXPECT_EQ(bytes[4 * 0 + 0], 0);
}

TEST(PngImage, FailedWriteKeepsTheExistingFile) {
  TempDir dir;
  write_png(ramp(2, 2), dir / "out.png");
  const std::string before = contents(dir / "out.png");
  // libpng refuses a zero-size image after the file is opened: the temporary must go away too.
  try {
    write_png(Image(0, 0), dir / "out.png");
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("out.png: cannot write PNG"), std::string::npos) << e.what();
  }
  EXPECT_EQ(contents(dir / "out.png"), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

TEST(PngImage, WriteIntoMissingDirectoryLeavesNothing) {
  TempDir dir;
  EXPECT_THROW(write_png(ramp(2, 2), dir / "missing" / "out.png"), InputError);
  EXPECT_TRUE(fs::is_empty(dir.path));
}

// Sets the RGB of pixel (x, y) of a hand-made image.
void set_rgb(Image& image, int x, int y, float r, float g, float b) {
  float* p = image.pixel(static_cast<std::size_t>(y) * image.width + x);
  p[0] = r, p[1] = g, p[2] = b;
}

Image uniform(int width, int height, float value) {
  Image image(width, height);
  for (std::size_t i = 0; i < image.pixel_count(); ++i) set_rgb(image, i % width, i / width, value, value, value);
  return image;
}

TEST(CompareImages, IdenticalImages) {
  const Image a = ramp(4, 3);
  const ErrorStats stats = compare_images(a, a, 1e-3);
  EXPECT_EQ(stats.pixels_compared, 12u);
  EXPECT_EQ(stats.max_abs, 0.0);
  EXPECT_EQ(stats.rmse, 0.0);
  EXPECT_TRUE(std::isinf(stats.psnr_db) && stats.psnr_db > 0);
  EXPECT_EQ(stats.nonfinite_mismatches, 0u);
}

TEST(CompareImages, WorstPixelIsByRelativeError) {
  Image expected = uniform(3, 2, 0.5f), test = uniform(3, 2, 0.5f);
  set_rgb(expected, 0, 0, 10.0f, 0.5f, 0.5f);
  set_rgb(test, 0, 0, 10.5f, 0.5f, 0.5f);  // largest absolute error (0.5) but relative only 0.05
  set_rgb(test, 2, 1, 0.5f, 0.625f, 0.5f);  // relative 0.25: the worst
  expected.data_window = {10, 20, 12, 21};  // coordinates are reported as the file states them

  const ErrorStats stats = compare_images(test, expected, 1e-3);
  EXPECT_EQ(stats.pixels_compared, 6u);
  // Tolerances: the inputs are exact binary fractions, only the final divisions/sqrt round.
  EXPECT_DOUBLE_EQ(stats.max_abs, 0.5);
  EXPECT_DOUBLE_EQ(stats.max_rel, 0.25);
  EXPECT_EQ(stats.worst_pixel, 5u);
  EXPECT_EQ(stats.worst_x, 12);
  EXPECT_EQ(stats.worst_y, 21);
  EXPECT_EQ(stats.worst_channel, 1);
  EXPECT_EQ(stats.worst_test, 0.625);
  EXPECT_EQ(stats.worst_expected, 0.5);
  const double rmse = std::sqrt((0.5 * 0.5 + 0.125 * 0.125) / 18.0);  // over 6 pixels x 3 channels
  EXPECT_DOUBLE_EQ(stats.rmse, rmse);
  EXPECT_DOUBLE_EQ(stats.psnr_db, 20.0 * std::log10(10.0 / rmse));  // peak = max |expected| = 10
}

TEST(CompareImages, FloorBoundsRelativeErrorNearZero) {
  Image expected = uniform(1, 1, 0.0f), test = uniform(1, 1, 0.0f);
  set_rgb(test, 0, 0, 0.0f, 0.0f, 0.015625f);
  // |t - e| / max(|e|, floor): with e = 0 the floor is the denominator.
  EXPECT_DOUBLE_EQ(compare_images(test, expected, 0.125).max_rel, 0.125);
  EXPECT_DOUBLE_EQ(compare_images(test, expected, 1.0 / 1024).max_rel, 16.0);
  set_rgb(expected, 0, 0, 0.0f, 0.0f, 0.5f);  // above the floor: |e| is the denominator
  EXPECT_DOUBLE_EQ(compare_images(test, expected, 0.125).max_rel, (0.5 - 0.015625) / 0.5);
}

TEST(CompareImages, NonFiniteValuesAreCountedNotMeasured) {
  Image expected = uniform(5, 1, 1.0f), test = uniform(5, 1, 1.0f);
  set_rgb(test, 0, 0, kNaN, 1.0f, 1.0f);          // NaN in test: mismatch
  set_rgb(expected, 1, 0, 1.0f, kNaN, 1.0f);      // NaN in expected: mismatch
  set_rgb(test, 2, 0, 1.0f, 1.0f, kInf);          // one infinite: mismatch
  set_rgb(test, 3, 0, kInf, 1.0f, 1.0f);          // equal infinities: a match
  set_rgb(expected, 3, 0, kInf, 1.0f, 1.0f);
  set_rgb(test, 4, 0, kInf, 1.0f, 1.0f);          // opposite infinities: mismatch
  set_rgb(expected, 4, 0, -kInf, 1.0f, 1.0f);
  const ErrorStats stats = compare_images(test, expected, 1e-3);
  EXPECT_EQ(stats.nonfinite_mismatches, 4u);
  EXPECT_EQ(stats.max_abs, 0.0);  // no NaN or Inf leaks into the finite metrics
  EXPECT_EQ(stats.rmse, 0.0);
  EXPECT_EQ(stats.pixels_compared, 5u);
}

TEST(CompareImages, MaskSelectsPixels) {
  Image expected = uniform(2, 2, 1.0f), test = uniform(2, 2, 1.0f);
  set_rgb(test, 1, 0, 3.0f, 1.0f, 1.0f);  // error outside the mask
  set_rgb(test, 0, 1, 1.5f, 1.0f, 1.0f);  // error inside
  const ErrorStats stats = compare_images(test, expected, 1e-3, {true, false, true, false});
  EXPECT_EQ(stats.pixels_compared, 2u);
  EXPECT_DOUBLE_EQ(stats.max_abs, 0.5);
  EXPECT_EQ(stats.worst_x, 0);
  EXPECT_EQ(stats.worst_y, 1);
}

TEST(CompareImages, MismatchedSizesAreRejected) {
  EXPECT_THROW(compare_images(Image(2, 3), Image(3, 2), 1e-3), std::invalid_argument);
  EXPECT_THROW(compare_images(Image(2, 2), Image(2, 2), 1e-3, {true}), std::invalid_argument);
}

}  // namespace
}  // namespace phongcl
