// Images: EXR round trips and what they carry, and the error metrics (PNGs: test_color.cpp).
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>

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

#include "cli_runner.h"  // read_text
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
  write_exr(written, dir / "out.exr", {.type = ExrPixelType::half});
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
  write_layered_exr({{"", &combined, true}, {"diffuse", &diffuse, false}}, dir / "half.exr", {.type = ExrPixelType::half});
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

// OpenEXR cuts a channel name to 255 bytes: a long layer's R, G and B became one channel, and two
// long names with one prefix one layer. Both are refused before anything is written.
TEST(ExrImage, LayersWhoseChannelNamesDoNotFitOrCollideAreRefused) {
  TempDir dir;
  const Image combined = ramp(5, 3), group = ramp(5, 3);
  const std::string fits(253, 'k');  // "k...k.R": 255 bytes
  write_layered_exr({{"", &combined, true}, {fits, &group, false}}, dir / "fits.exr");
  const Plane green = decode_with_openexr(dir / "fits.exr", fits + ".G");
  EXPECT_EQ(green[1], group.pixel(1)[1]);
  fs::remove(dir / "fits.exr");

  const struct {
    const char* what;
    std::vector<ExrLayer> layers;
    std::string expected;
  } refused[] = {
      {"a 300-byte name", {{"", &combined, true}, {std::string(300, 'k'), &group, false}}, "longer than 255 bytes"},
      {"a 254-byte name", {{"", &combined, true}, {std::string(254, 'k'), &group, false}}, "longer than 255 bytes"},
      {"one name twice", {{"", &combined, true}, {"group.key", &group, false}, {"group.key", &group, false}},
       "'group.key.R' twice"},
      {"two unnamed layers", {{"", &combined, true}, {"", &group, false}}, "'R' twice"},
  };
  for (const auto& refusal : refused) {
    SCOPED_TRACE(refusal.what);
    try {
      write_layered_exr(refusal.layers, dir / "layers.exr");
      ADD_FAILURE() << "written";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(refusal.expected), std::string::npos) << error.what();
    }
    EXPECT_TRUE(fs::is_empty(dir.path)) << "no file and no temporary file";
  }
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

// Premultiplied RGBA: colour where alpha is 0 is light a compositor's `over` adds to the plate.
Image with_background_colour() {
  Image image = ramp(3, 2);
  float* sky = image.pixel(4);
  sky[0] = 0.05f, sky[1] = 0.06f, sky[2] = 0.1f, sky[3] = 0.0f;  // what the shader leaves there
  image.pixel(1)[3] = 0.5f;                                         // a partly covered edge keeps its colour
  return image;
}

TEST(ExrImage, TransparentPixelsAreWrittenWithoutColour) {
  TempDir dir;
  const Image written = with_background_colour();
  write_exr(written, dir / "out.exr");
  const Image read = read_exr(dir / "out.exr");
  for (std::size_t i = 0; i < written.pixel_count(); ++i)
    for (int c = 0; c < 4; ++c)
      EXPECT_EQ(read.pixel(i)[c], i == 4 && c < 3 ? 0.0f : written.pixel(i)[c]) << "pixel " << i << " channel " << c;
  EXPECT_EQ(written.pixel(4)[0], 0.05f) << "the caller's image is left as it was";
}

TEST(ExrImage, TransparentColourIsKeptOnRequest) {
  TempDir dir;
  const Image written = with_background_colour();
  write_exr(written, dir / "out.exr", {.keep_color_where_transparent = true});
  EXPECT_EQ(read_exr(dir / "out.exr").rgba, written.rgba);
}

TEST(ExrImage, LayersLoseColourWhereTheirAlphaIsZero) {
  TempDir dir;
  const Image combined = with_background_colour();
  Image diffuse = combined;  // terms carry the combined image's alpha
  diffuse.pixel(4)[1] = 7.0f;
  write_layered_exr({{"", &combined, true}, {"diffuse", &diffuse, false}}, dir / "layers.exr");
  const Plane green = decode_with_openexr(dir / "layers.exr", "diffuse.G");
  EXPECT_EQ(green[4], 0.0f);
  EXPECT_EQ(green[1], diffuse.pixel(1)[1]);
}

TEST(ExrImage, ChromaticitiesAreTheStandardAttribute) {
  TempDir dir;
  write_exr(ramp(2, 2), dir / "plain.exr");
  EXPECT_FALSE(Imf::hasChromaticities(Imf::InputFile((dir / "plain.exr").c_str()).header()));
  const Chromaticities p3{{0.68f, 0.32f}, {0.265f, 0.69f}, {0.15f, 0.06f}, {0.3127f, 0.329f}};
  write_exr(ramp(2, 2), dir / "p3.exr", {.chromaticities = p3});
  const Imf::Header header = Imf::InputFile((dir / "p3.exr").c_str()).header();
  ASSERT_TRUE(Imf::hasChromaticities(header));
  const Imf::Chromaticities& c = Imf::chromaticities(header);
  EXPECT_EQ(c.red.x, 0.68f);
  EXPECT_EQ(c.green.y, 0.69f);
  EXPECT_EQ(c.blue.x, 0.15f);
  EXPECT_EQ(c.white.y, 0.329f);
}

// What `phongcl serve` sends: the bytes write_exr writes, made in memory.
TEST(ExrImage, EncodedInMemoryIsWhatWriteExrWrites) {
  TempDir dir;
  Image image = ramp(5, 3);
  image.pixel(0)[3] = 0.0f;  // its colour is cleared in both
  const Chromaticities p3{{0.68f, 0.32f}, {0.265f, 0.69f}, {0.15f, 0.06f}, {0.3127f, 0.329f}};
  for (const ExrPixelType type : {ExrPixelType::float32, ExrPixelType::half}) {
    const ExrWriteOptions options{.type = type, .chromaticities = p3};
    write_exr(image, dir / "frame.exr", options);
    const std::string file = testing::read_text(dir / "frame.exr"), memory = encode_exr(image, options);
    EXPECT_TRUE(memory == file) << "in memory " << memory.size() << " bytes, the file " << file.size();
  }
}

TEST(ExrImage, WriteIntoMissingDirectoryLeavesNothing) {
  TempDir dir;
  EXPECT_THROW(write_exr(ramp(2, 2), dir / "missing" / "out.exr"), InputError);
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
