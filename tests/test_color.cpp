// Colour management (host/color): the built-in config against the curves it replaced, display
// transforms against OpenColorIO's own processor, its ocioconvert tool and Blender's own PNGs, the
// flattening and exposure rules, the AVX2 loops against the scalar ones, colour spaces in, and the
// working space's chromaticities.
#include <gtest/gtest.h>
#include <png.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <OpenColorIO/OpenColorIO.h>
#include <phongcl/relighter.hpp>

#include "cli_runner.h"
#include "color/builtin_config.h"
#include "color/byte_steps.h"
#include "color/color_conversion.h"
#include "color/display.h"
#include "color/display_math.h"
#include "color/display_processor.h"
#include "color/pixel_kernels.h"
#include "common/error.h"
#include "image/image.h"
#include "opencl_required.h"
#include "scene/scene.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;
namespace OCIO = OCIO_NAMESPACE;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
const fs::path kFixtures = PHONGCL_SOURCE_DIR "/tests/fixtures/colour";

using testing::TempDir;

// ---- Oracles, written out apart from the product ----

// The curves phongcl's PNGs had before OCIO (host/image/display_bytes.cpp): exposure, tone curve,
// the exact sRGB encoding, lround to 8 bits; NaN and negatives black, +Inf white.
int old_display_byte(float value, const std::string& view, double exposure) {
  const double x = value * std::exp2(exposure);
  if (std::isnan(x) || x <= 0.0) return 0;
  if (std::isinf(x)) return 255;
  const double t = view == "clamp" ? std::min(x, 1.0) : view == "reinhard" ? x / (1.0 + x)
                 : std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
  const double s = t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1.0 / 2.4) - 0.055;
  return static_cast<int>(std::lround(std::clamp(s, 0.0, 1.0) * 255.0));
}

double srgb_encode(double linear) { return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055; }
double srgb_decode(double encoded) { return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4); }

// Round half up, as Blender (and the display transform) turn display values into bytes.
int byte_of(float v) { return v > 0.0f ? (v < 1.0f - 0.5f / 255.0f ? static_cast<int>(v * 255.0f + 0.5f) : 255) : 0; }

// ---- Helpers ----

Image gray_row(const std::vector<float>& values) {
  Image image(static_cast<int>(values.size()), 1);
  for (std::size_t i = 0; i < values.size(); ++i) {
    float* p = image.pixel(i);
    p[0] = p[1] = p[2] = values[i];
    p[3] = 1.0f;
  }
  return image;
}

DisplaySettings settings_of(const std::string& view, const std::string& look = "", double exposure = 0.0) {
  DisplaySettings settings;
  settings.view = view;
  settings.look = look;
  settings.exposure_stops = exposure;
  return settings;
}

std::vector<std::uint8_t> read_png_rgb(const fs::path& file, int& width, int& height) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, file.c_str())) throw std::runtime_error(png.message);
  png.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> bytes(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr)) throw std::runtime_error(png.message);
  width = static_cast<int>(png.width);
  height = static_cast<int>(png.height);
  return bytes;
}

// Blender's OCIO config where Blender is installed (Debian's blender package); tests that need it
// report SKIP elsewhere.
std::optional<ColorConfig> blender_config() {
  try {
    return ColorConfig::load("blender");
  } catch (const InputError&) {
    return std::nullopt;
  }
}

#define REQUIRE_BLENDER_CONFIG(config)                                                          \
  const std::optional<ColorConfig> config = blender_config();                                   \
  if (!config) GTEST_SKIP() << "Blender's OCIO config is not installed (scripts/setup.sh blender)"

// Colours a frame can hold: log-spread channels over 2^-14..2^12, near-greys, zeros, exact powers
// of two, from a fixed seed; alpha 1.
Image test_colors(int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> stops(-14.0, 12.0), near(-0.25, 0.25);
  Image image(count, 1);
  for (int i = 0; i < count; ++i) {
    float* p = image.pixel(i);
    const double base = stops(random);
    for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(std::exp2(i % 3 ? stops(random) : base + near(random)));
    if (i % 101 == 0) p[i % 3] = 0.0f;
    if (i % 97 == 0) p[0] = p[1] = p[2] = static_cast<float>(std::exp2(i % 20 - 10));
    p[3] = 1.0f;
  }
  return image;
}

// Bytes of the display transform against OpenColorIO's processor of the same view on the same
// (exposed) values.
struct Agreement {
  double identical = 0.0, within_one = 0.0;
  int worst = 0;
};
Agreement against_ocio(const ColorConfig& config, const DisplaySettings& settings, const Image& image) {
  const DisplayTransform display(config, settings);
  const std::vector<std::uint8_t> ours = display.encode(image);
  std::vector<float> exact(3 * image.pixel_count());
  const float scale = static_cast<float>(std::exp2(settings.exposure_stops));
  for (std::size_t i = 0; i < image.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) exact[3 * i + c] = image.pixel(i)[c] * scale;
  OCIO::PackedImageDesc packed(exact.data(), static_cast<long>(image.pixel_count()), 1, 3);
  display_processor(config, display.display(), display.view(), display.look())->getDefaultCPUProcessor()->apply(packed);
  Agreement agreement;
  std::size_t identical = 0, within = 0;
  for (std::size_t i = 0; i < image.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const int difference = std::abs(ours[4 * i + c] - byte_of(exact[3 * i + c]));
      identical += difference == 0;
      within += difference <= 1;
      agreement.worst = std::max(agreement.worst, difference);
    }
  agreement.identical = static_cast<double>(identical) / (3.0 * image.pixel_count());
  agreement.within_one = static_cast<double>(within) / (3.0 * image.pixel_count());
  return agreement;
}

// ---- The built-in config against the curves it replaced ----

TEST(BuiltinConfig, ViewsReproduceTheCurvesTheyReplaced) {
  // A geometric sweep over 2^-20..2^20 (1e-4 apart), and every float near a byte boundary the
  // sweep crosses, at exposures that move the boundaries off the sweep's points.
  const ColorConfig config = ColorConfig::builtin();
  std::vector<float> sweep;
  for (double x = std::exp2(-20.0); x < std::exp2(20.0); x *= 1.0001) sweep.push_back(static_cast<float>(x));
  for (const double exposure : {0.0, -3.7, 2.3, -40.0, 40.0}) {
    for (const std::string view : {"clamp", "reinhard", "aces"}) {
      std::vector<float> values = sweep;
      for (std::size_t i = 1; i < sweep.size(); ++i)
        if (old_display_byte(sweep[i], view, exposure) != old_display_byte(sweep[i - 1], view, exposure))
          for (float v = sweep[i - 1]; v <= sweep[i] && values.size() < 2 * sweep.size(); v = std::nextafter(v, 2 * v))
            values.push_back(v);
      const std::vector<std::uint8_t> bytes = DisplayTransform(config, settings_of(view, "", exposure)).encode(gray_row(values));
      std::size_t identical = 0;
      for (std::size_t i = 0; i < values.size(); ++i) {
        const int old = old_display_byte(values[i], view, exposure);
        identical += i < sweep.size() && bytes[4 * i] == old;
        ASSERT_LE(std::abs(bytes[4 * i] - old), 1) << "value " << values[i] << " view " << view << " exposure " << exposure;
      }
      // The views are OCIO ops (a half-domain LUT, the sRGB curve) and bytes come from a table of
      // them: a byte may round the other way only where the curve is within a hair of a step, which
      // the values added next to each step seek out; on the even sweep nearly every byte is the same.
      EXPECT_GE(static_cast<double>(identical) / sweep.size(), 0.999) << view << " exposure " << exposure;
    }
  }
}

TEST(BuiltinConfig, KnownPointsThroughAPngFile) {
  // Expected bytes by hand from the formulas, each at least 0.08 away from a rounding boundary.
  struct Case {
    float value;
    const char* view;
    double exposure;
    int byte;
    const char* why;
  };
  const Case cases[] = {
      {1.0f, "reinhard", 0.0, 188, "1/(1+1) = 0.5, sRGB 0.7354 (a 2.2 gamma would give 186)"},
      {3.0f, "reinhard", 0.0, 225, "0.75 -> sRGB 0.8808"},
      {0.5f, "reinhard", 1.0, 188, "one stop up makes it 1"},
      {0.2f, "clamp", 0.0, 124, "sRGB(0.2) = 0.4845"},
      {0.002f, "clamp", 0.0, 7, "linear segment: 12.92 * 0.002"},
      {2.0f, "clamp", 0.0, 255, "clamped to 1"},
      {1.0f, "aces", 0.0, 232, "2.54/3.16 = 0.8038 -> sRGB 0.9082"},
      {0.18f, "aces", 0.0, 141, "0.2669 -> sRGB 0.5535"},
      {-1.0f, "reinhard", 0.0, 0, "negative displays as black"},
      {kNaN, "aces", 0.0, 0, "NaN displays as black"},
      {kInf, "reinhard", 0.0, 255, "+Inf displays as white"},
      {kInf, "aces", 0.0, 255, "+Inf displays as white"},
      {kInf, "clamp", -40.0, 255, "+Inf stays white whatever the exposure"},
  };
  TempDir dir;
  for (const Case& c : cases) {
    DisplaySettings settings = settings_of(c.view, "", c.exposure);
    write_png(dir / "out.png", gray_row({c.value}), settings);
    int width = 0, height = 0;
    const auto bytes = read_png_rgb(dir / "out.png", width, height);
    ASSERT_EQ(bytes.size(), 3u);
    for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(bytes[ch], c.byte) << "value " << c.value << " " << c.view << ": " << c.why;
  }
}

std::string contents(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(PngFile, SizeRowOrderAndTheSrgbTag) {
  TempDir dir;
  Image image(3, 2);
  for (std::size_t i = 0; i < image.pixel_count(); ++i) image.pixel(i)[3] = 1.0f;
  image.pixel(3)[0] = 1.0f;  // red marks the first pixel of the second row
  write_png(dir / "out.png", image, settings_of("clamp"));
  EXPECT_NE(contents(dir / "out.png").find("sRGB"), std::string::npos) << "the sRGB chunk tags the encoding";
  int width = 0, height = 0;
  const auto bytes = read_png_rgb(dir / "out.png", width, height);
  EXPECT_EQ(width, 3);
  EXPECT_EQ(height, 2);
  EXPECT_EQ(bytes[3 * 3], 255);
  EXPECT_EQ(bytes[0], 0);
}

TEST(PngFile, FailedWriteKeepsTheExistingFile) {
  TempDir dir;
  write_png(dir / "out.png", gray_row({0.5f, 0.25f}));
  const std::string before = contents(dir / "out.png");
  // libpng refuses a zero-size image after the file is opened: the temporary must go away too.
  try {
    write_png(dir / "out.png", Image(0, 0));
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("out.png: cannot write PNG"), std::string::npos) << e.what();
  }
  EXPECT_EQ(contents(dir / "out.png"), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

TEST(PngFile, WriteIntoMissingDirectoryLeavesNothing) {
  TempDir dir;
  EXPECT_THROW(write_png(dir / "missing" / "out.png", gray_row({0.5f})), InputError);
  EXPECT_TRUE(fs::is_empty(dir.path));
}

TEST(BuiltinConfig, IsTheDefaultWithoutTheOcioVariable) {
  const char* saved = std::getenv("OCIO");
  const std::string restore = saved ? saved : "";
  unsetenv("OCIO");
  const ColorConfig config = ColorConfig::load();
  EXPECT_EQ(config.description(), ColorConfig::builtin().description());
  EXPECT_EQ(config.working_space(), "Linear Rec.709 (sRGB)");
  EXPECT_EQ(config.default_view(config.default_display()), "reinhard");
  if (saved) setenv("OCIO", restore.c_str(), 1);
}

// ---- What a display transform draws ----

TEST(DisplayTransform, FlattensThePremultipliedImageOverTheBackground) {
  const ColorConfig config = ColorConfig::builtin();
  DisplaySettings settings = settings_of("clamp");
  settings.background = {0.05, 0.2, 0.6};
  struct Case {
    float rgba[4];
    double expected[3];  // linear, before sRGB
    const char* why;
  };
  const Case cases[] = {
      {{0.3f, 0.1f, 0.7f, 1.0f}, {0.3, 0.1, 0.7}, "opaque: the colour"},
      {{5.0f, 5.0f, 5.0f, 0.0f}, {0.05, 0.2, 0.6}, "alpha 0: the background, whatever colour the pixel holds"},
      {{0.1f, 0.1f, 0.1f, 0.5f}, {0.125, 0.2, 0.4}, "half covered: colour + (1 - alpha) * background"},
      {{0.3f, 0.1f, 0.7f, 2.0f}, {0.3, 0.1, 0.7}, "alpha above 1 counts as 1"},
      {{0.3f, 0.1f, 0.7f, kNaN}, {0.05, 0.2, 0.6}, "NaN alpha counts as 0"},
      {{kNaN, 0.1f, 0.7f, 1.0f}, {0.0, 0.1, 0.7}, "NaN colour is 0"},
  };
  for (const Case& c : cases) {
    Image image(1, 1);
    std::copy(c.rgba, c.rgba + 4, image.pixel(0));
    const std::vector<std::uint8_t> bytes = DisplayTransform(config, settings).encode(image);
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(bytes[ch], 255.0 * srgb_encode(c.expected[ch]), 0.5 + 1e-3) << c.why << ", channel " << ch;
    EXPECT_EQ(bytes[3], 255) << c.why << ": previews are opaque";
  }
  // The same through a view of per-pixel stages (a 3D LUT), against OpenColorIO on the flattened values.
  const std::optional<ColorConfig> blender = blender_config();
  if (!blender) GTEST_SKIP() << "Blender's OCIO config is not installed (scripts/setup.sh blender)";
  DisplaySettings filmic = settings_of("Filmic");
  filmic.background = settings.background;
  const DisplayTransform display(*blender, filmic);
  ASSERT_EQ(display.pipeline().find("exact byte steps"), std::string::npos) << display.pipeline();
  const auto ocio = display_processor(*blender, display.display(), display.view(), display.look())->getDefaultCPUProcessor();
  for (const Case& c : cases) {
    Image image(1, 1);
    std::copy(c.rgba, c.rgba + 4, image.pixel(0));
    const std::vector<std::uint8_t> bytes = display.encode(image);
    float expected[3] = {static_cast<float>(c.expected[0]), static_cast<float>(c.expected[1]), static_cast<float>(c.expected[2])};
    ocio->applyRGB(expected);
    for (int ch = 0; ch < 3; ++ch) EXPECT_LE(std::abs(bytes[ch] - byte_of(expected[ch])), 1) << c.why << ", Filmic, channel " << ch;
  }
}

TEST(ByteSteps, EqualTheCurveTheyStep) {
  // sRGB of x / (1 + x) at one stop of exposure: each float near a step, and a sweep.
  const auto curve = [](float v) { return display_byte(static_cast<float>(srgb_encode(reinhard_curve(2.0 * v)))); };
  const std::optional<ByteSteps> steps = ByteSteps::make(curve);
  ASSERT_TRUE(steps);
  std::vector<float> values = {0.0f, -0.0f, -1.0f, kNaN, kInf, std::numeric_limits<float>::max(), std::numeric_limits<float>::denorm_min()};
  for (double x = std::exp2(-30.0); x < std::exp2(30.0); x *= 1.001) {
    const float v = static_cast<float>(x);
    values.push_back(v);
    if (curve(v) != curve(std::nextafter(v, 0.0f)))
      for (float near = std::nextafter(v, 0.0f), k = 0; k < 4; ++k, near = std::nextafter(near, 0.0f)) values.push_back(near);
  }
  for (const float v : values) ASSERT_EQ((*steps)(v), std::isnan(v) || v < 0.0f ? curve(0.0f) : curve(v)) << "value " << v;
  // A curve that climbs from 0 to 255 within one bucket of the table (0.8% of the value) is refused.
  EXPECT_FALSE(ByteSteps::make([](float v) { return display_byte(std::clamp((v - 1.0f) * 1000.0f, 0.0f, 1.0f)); }));
}

TEST(DisplayTransform, ExposureScalesTheWorkingValuesBeforeTheView) {
  REQUIRE_BLENDER_CONFIG(blender);
  const Image image = test_colors(4096, 7);
  for (const double stops : {2.0, -3.0}) {  // powers of two: the scaled image is exact
    Image scaled = image;
    for (std::size_t i = 0; i < scaled.pixel_count(); ++i)
      for (int c = 0; c < 3; ++c) scaled.pixel(i)[c] *= static_cast<float>(std::exp2(stops));
    for (const char* view : {"Filmic", "Standard"})
      EXPECT_EQ(DisplayTransform(*blender, settings_of(view, "", stops)).encode(image),
                DisplayTransform(*blender, settings_of(view)).encode(scaled))
          << view << " exposure " << stops;
  }
}

TEST(DisplayTransform, NamesNotInTheConfigAreErrorsThatListWhatIs) {
  const ColorConfig config = ColorConfig::builtin();
  const auto message = [&](const DisplaySettings& settings) {
    try {
      DisplayTransform(config, settings);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(settings_of("Filmic")).find("display 'sRGB' has no view 'Filmic' (views: reinhard, aces, clamp)"),
            std::string::npos)
      << message(settings_of("Filmic"));
  DisplaySettings xyz;
  xyz.display = "XYZ";
  EXPECT_NE(message(xyz).find("no display 'XYZ' (displays: sRGB)"), std::string::npos) << message(xyz);
  EXPECT_NE(message(settings_of("", "Punchy")).find("no look 'Punchy' (looks: none)"), std::string::npos);
  for (const double exposure : {static_cast<double>(kNaN), static_cast<double>(kInf), 65.0, -1e300})
    EXPECT_THROW(DisplayTransform(config, settings_of("", "", exposure)), std::invalid_argument) << exposure;
  DisplaySettings infinite_background;
  infinite_background.background.g = kInf;
  EXPECT_THROW(DisplayTransform(config, infinite_background), std::invalid_argument);
}

TEST(DisplayTransform, EveryViewIsCompiledAndAgreesWithOpenColorIO) {
  // Colours from a seed the compiled pipeline's own check does not use.
  const Image colors = test_colors(60000, 2024);
  const ColorConfig builtin = ColorConfig::builtin();
  for (const char* view : {"reinhard", "aces", "clamp"}) {
    EXPECT_EQ(DisplayTransform(builtin, settings_of(view)).pipeline().rfind("compiled:", 0), 0u) << view;
    const Agreement a = against_ocio(builtin, settings_of(view), colors);
    EXPECT_EQ(a.worst, 1) << view;
    EXPECT_GE(a.identical, 0.999) << view;
  }
}

TEST(DisplayTransform, BlenderViewsAndEveryLookAgreeWithOpenColorIO) {
  REQUIRE_BLENDER_CONFIG(blender);
  const Image colors = test_colors(60000, 2025);
  std::vector<DisplaySettings> cases = {settings_of("Standard"), settings_of("Filmic"), settings_of("Filmic Log"),
                                        settings_of("False Color"), settings_of("Filmic", "", 1.5)};
  for (const std::string& look : blender->looks()) cases.push_back(settings_of("Filmic", look));
  cases.push_back(settings_of("Standard", "High Contrast"));
  for (const DisplaySettings& settings : cases) {
    const std::string name = settings.view + " " + settings.look;
    EXPECT_EQ(DisplayTransform(*blender, settings).pipeline().rfind("compiled:", 0), 0u) << name;
    const Agreement a = against_ocio(*blender, settings, colors);
    EXPECT_LE(a.worst, 1) << name;
    EXPECT_GE(a.identical, 0.99) << name;
  }
}

TEST(PixelKernels, Avx2AgreesWithTheScalarLoops) {
  const PixelKernels* avx2 = avx2_pixel_kernels();
  if (!avx2) GTEST_SKIP() << "this CPU has no AVX2 and FMA";
  const PixelKernels& scalar = scalar_pixel_kernels();
  constexpr std::size_t n = 1003;  // a tail of 3 after the 8-wide steps
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit(-0.2f, 1.2f), wide(-20.0f, 20.0f);
  std::vector<float> rgba(4 * n);
  for (std::size_t i = 0; i < rgba.size(); ++i) rgba[i] = i % 4 == 3 ? unit(random) : std::exp2(wide(random));
  rgba[5] = kNaN, rgba[11] = kNaN, rgba[40] = kInf;
  struct Planes {
    std::vector<float> r = std::vector<float>(n), g = r, b = r;
    float* p[3] = {r.data(), g.data(), b.data()};
  } a, b;
  const float background[3] = {0.1f, 0.2f, 0.3f};
  scalar.flatten(rgba.data(), n, background, 1.5f, a.p);
  avx2->flatten(rgba.data(), n, background, 1.5f, b.p);
  for (int c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(a.p[c][i], b.p[c][i]) << "flatten, pixel " << i << " channel " << c;

  std::vector<float> table(65537);
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = static_cast<float>(std::sin(i * 1e-3));
  const float* tables[3] = {table.data(), table.data(), table.data()};
  scalar.separable(tables, a.p, n);
  avx2->separable(tables, b.p, n);
  const auto expect_close = [&](const char* what) {
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_NEAR(a.p[c][i], b.p[c][i], 4e-7 * std::max(1.0f, std::abs(a.p[c][i]))) << what << ", pixel " << i << " channel " << c;
  };
  expect_close("separable");  // fused multiply-adds round once

  constexpr int size = 9;
  std::vector<float> lut(3 * size * size * size + 1);  // + the padding the AVX2 loop reads
  for (std::size_t i = 0; i < lut.size(); ++i) lut[i] = unit(random);
  for (const bool tetrahedral : {true, false}) {
    Planes x = a, y = a;
    x.p[0] = x.r.data(), x.p[1] = x.g.data(), x.p[2] = x.b.data();
    y.p[0] = y.r.data(), y.p[1] = y.g.data(), y.p[2] = y.b.data();
    for (std::size_t i = 0; i < n; i += 17) x.r[i] = y.r[i] = x.g[i] = y.g[i] = 0.5f;  // ties between fractions
    scalar.lut3d(lut.data(), size, tetrahedral, x.p, n);
    avx2->lut3d(lut.data(), size, tetrahedral, y.p, n);
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_NEAR(x.p[c][i], y.p[c][i], 1e-6) << (tetrahedral ? "tetrahedral" : "trilinear") << ", pixel " << i;
  }
  const float m[3][3] = {{1.2f, -0.1f, 0.3f}, {0.0f, 0.9f, 0.1f}, {-0.2f, 0.4f, 1.1f}}, offset[3] = {0.01f, 0.0f, -0.02f};
  scalar.matrix(m, offset, a.p, n);
  avx2->matrix(m, offset, b.p, n);
  expect_close("matrix");

  for (std::size_t i = 0; i < n; ++i) a.r[i] = b.r[i] = unit(random);
  a.g[7] = b.g[7] = kNaN;
  std::vector<std::uint8_t> bytes_a(4 * n), bytes_b(4 * n);
  scalar.to_bytes(a.p, n, bytes_a.data());
  avx2->to_bytes(b.p, n, bytes_b.data());
  for (std::size_t i = 0; i < bytes_a.size(); ++i) ASSERT_LE(std::abs(bytes_a[i] - bytes_b[i]), 1) << "byte " << i;
  EXPECT_EQ(bytes_b[4 * 7 + 1], 0) << "NaN is black";
  EXPECT_EQ(bytes_b[3], 255) << "opaque";
}

// ---- Against OpenColorIO's own tool and Blender's own PNGs ----

// Runs a shell command; its exit status.
int run(const std::string& command) { return std::system((command + " >/dev/null 2>&1").c_str()); }

// Blender's config with, for each look, a view that applies it (a view's looks: OpenColorIO's own
// way to name "Filmic with this look"), its LUT search path made absolute.
fs::path config_with_look_views(const fs::path& blender_file, const fs::path& directory, const std::vector<std::string>& looks) {
  std::ifstream in(blender_file);
  std::stringstream text;
  text << in.rdbuf();
  std::string config = text.str();
  const std::string luts = blender_file.parent_path().string();
  const std::string search = "search_path: \"luts:filmic\"";
  config.replace(config.find(search), search.size(), "search_path: \"" + luts + "/luts:" + luts + "/filmic\"");
  std::string views;
  for (const std::string& look : looks)
    views += "    - !<View> {name: Filmic " + look + ", colorspace: Filmic sRGB, looks: " + look + "}\n";
  const std::string display = "  sRGB:\n";
  config.insert(config.find(display) + display.size(), views);
  const std::string active = "active_views: [";
  config.erase(config.find(active), config.find('\n', config.find(active)) - config.find(active));  // every view active
  std::ofstream(directory / "config.ocio") << config;
  return directory / "config.ocio";
}

TEST(Ocioconvert, SameBytesForBlendersViewsLooksAndExposures) {
  if (run("command -v ocioconvert") != 0) GTEST_SKIP() << "ocioconvert is not installed (scripts/setup.sh colour)";
  REQUIRE_BLENDER_CONFIG(blender);
  TempDir dir;
  const fs::path config_file = config_with_look_views(ColorConfig::blender_config_file(), dir.path, blender->looks());
  // A shaded frame's values and spread colours, in one image.
  Image image = read_exr(kFixtures / "lit.exr");
  const Image colors = test_colors(image.width * 40, 99);
  Image both(image.width, image.height + 40);
  std::copy(image.rgba.begin(), image.rgba.end(), both.rgba.begin());
  std::copy(colors.rgba.begin(), colors.rgba.end(), both.rgba.begin() + image.rgba.size());
  for (std::size_t i = 0; i < both.pixel_count(); ++i) both.pixel(i)[3] = 1.0f;  // ocioconvert does not flatten

  struct Case {
    std::string view, look;
    double exposure;
  };
  std::vector<Case> cases = {{"Standard", "", 0.0}, {"Filmic", "", 0.0}, {"Filmic", "", -2.0}, {"Standard", "", 1.5}};
  for (const std::string& look : blender->looks()) cases.push_back({"Filmic", look, 0.0});
  for (const Case& c : cases) {
    Image exposed = both;  // ocioconvert has no exposure: scale the values it reads
    for (std::size_t i = 0; i < exposed.pixel_count(); ++i)
      for (int ch = 0; ch < 3; ++ch) exposed.pixel(i)[ch] *= static_cast<float>(std::exp2(c.exposure));
    write_exr(exposed, dir / "in.exr");
    const std::string view = c.look.empty() ? c.view : "Filmic " + c.look;
    ASSERT_EQ(run("OCIO='" + config_file.string() + "' ocioconvert --view '" + (dir / "in.exr").string() + "' Linear '" +
                  (dir / "out.exr").string() + "' sRGB '" + view + "'"),
              0)
        << view;
    const Image expected = read_exr(dir / "out.exr");
    const std::vector<std::uint8_t> ours = DisplayTransform(*blender, settings_of(c.view, c.look, c.exposure)).encode(both);
    std::size_t identical = 0;
    for (std::size_t i = 0; i < both.pixel_count(); ++i)
      for (int ch = 0; ch < 3; ++ch) {
        const int difference = std::abs(ours[4 * i + ch] - byte_of(expected.pixel(i)[ch]));
        ASSERT_LE(difference, 1) << view << " exposure " << c.exposure << " pixel " << i;
        identical += difference == 0;
      }
    EXPECT_GE(static_cast<double>(identical) / (3.0 * both.pixel_count()), 0.99) << view;
  }
}

TEST(BlenderFixtures, PngsEqualBlendersOwnWithin1Over255) {
  REQUIRE_BLENDER_CONFIG(blender);
  // tests/fixtures/colour: made by scripts/blender/make_colour_fixtures.sh (Blender 3.4).
  const Image lit = read_exr(kFixtures / "lit.exr");
  const glm::dvec3 background = load_scene(PHONGCL_SOURCE_DIR "/scenes/default/scene.json").background;
  std::ifstream cases(kFixtures / "cases.txt");
  int checked = 0;
  for (std::string line; std::getline(cases, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream parts(line);
    for (std::string field; std::getline(parts, field, '|');) {
      field.erase(0, field.find_first_not_of(' '));
      field.erase(field.find_last_not_of(' ') + 1);
      fields.push_back(field);
    }
    ASSERT_EQ(fields.size(), 4u) << line;
    DisplaySettings settings = settings_of(fields[1], fields[2], std::stod(fields[3]));
    settings.background = background;
    const std::vector<std::uint8_t> ours = DisplayTransform(*blender, settings).encode(lit);
    int width = 0, height = 0;
    const std::vector<std::uint8_t> theirs = read_png_rgb(kFixtures / "blender" / (fields[0] + ".png"), width, height);
    ASSERT_EQ(width, lit.width);
    ASSERT_EQ(height, lit.height);
    std::size_t within = 0;
    for (std::size_t i = 0; i < lit.pixel_count(); ++i) {
      int difference = 0;
      for (int c = 0; c < 3; ++c) difference = std::max(difference, std::abs(ours[4 * i + c] - theirs[3 * i + c]));
      within += difference <= 1;
    }
    EXPECT_GE(static_cast<double>(within) / lit.pixel_count(), 0.999) << fields[0];
    ++checked;
  }
  EXPECT_EQ(checked, 12);
}

// ---- The config: loading, chromaticities ----

TEST(ColorConfig, LoadErrorsNameTheFile) {
  TempDir dir;
  const auto message = [](const std::string& which) {
    try {
      ColorConfig::load(which);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message((dir / "absent.ocio").string()).find("absent.ocio: cannot read the OCIO config: no such file"),
            std::string::npos);
  std::filesystem::create_directory(dir / "folder.ocio");
  EXPECT_NE(message((dir / "folder.ocio").string()).find("folder.ocio: cannot read the OCIO config: it is a directory"),
            std::string::npos);
  std::ofstream(dir / "bad.ocio") << "ocio_profile_version: 2\nroles: [unclosed\n";
  const std::string bad = message((dir / "bad.ocio").string());
  EXPECT_NE(bad.find("bad.ocio: not a usable OCIO config"), std::string::npos) << bad;
  EXPECT_EQ(bad.find('\n'), std::string::npos) << "one line";
  const char* saved = std::getenv("OCIO");
  const std::string restore = saved ? saved : "";
  setenv("OCIO", (dir / "absent.ocio").c_str(), 1);
  EXPECT_NE(message("").find("the OCIO environment variable names"), std::string::npos) << message("");
  if (saved) setenv("OCIO", restore.c_str(), 1);
  else unsetenv("OCIO");
}

void expect_rec709(const Chromaticities& c) {
  const std::pair<std::array<float, 2>, std::array<float, 2>> expected[] = {
      {c.red, {0.64f, 0.33f}}, {c.green, {0.30f, 0.60f}}, {c.blue, {0.15f, 0.06f}}, {c.white, {0.3127f, 0.3290f}}};
  for (const auto& [got, want] : expected)
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(got[i], want[i], 2e-4);  // the configs' matrices carry 4-7 digits
}

TEST(ColorConfig, WorkingChromaticitiesFromTheAcesInterchangeRole) {
  const auto builtin = ColorConfig::builtin().working_chromaticities();
  ASSERT_TRUE(builtin);
  expect_rec709(*builtin);
  REQUIRE_BLENDER_CONFIG(blender);
  const auto from_blender = blender->working_chromaticities();
  ASSERT_TRUE(from_blender) << "Blender's config states aces_interchange";
  expect_rec709(*from_blender);
}

// ---- Colour spaces in ----

TEST(ColorConversion, SrgbAndAcescgIntoTheWorkingSpace) {
  const ColorConfig config = ColorConfig::builtin();
  const ColorConversion from_srgb(config, "sRGB", "test");
  for (const double v : {0.0, 0.02, 0.04045, 0.2, 0.5, 0.9, 1.0})
    EXPECT_NEAR(from_srgb({v, v, v}).g, srgb_decode(v), 1e-6) << v;
  // AP1 to Rec.709 with the Bradford adaptation from ACES's white to D65 (the ACES project's
  // published matrix, to 4 digits).
  const ColorConversion from_acescg(config, "ACEScg", "test");
  const glm::dvec3 red = from_acescg({1, 0, 0}), green = from_acescg({0, 1, 0});
  EXPECT_NEAR(red.r, 1.7051, 2e-4);
  EXPECT_NEAR(red.g, -0.1302, 2e-4);
  EXPECT_NEAR(green.r, -0.6218, 2e-4);
  EXPECT_NEAR(green.g, 1.1408, 2e-4);
  EXPECT_TRUE(ColorConversion(config, "Linear Rec.709 (sRGB)", "test").is_identity());
  EXPECT_TRUE(ColorConversion(config, "scene_linear", "test").is_identity()) << "roles name spaces too";
  try {
    ColorConversion(config, "Rec.2020", "--gbuffer-space");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("--gbuffer-space 'Rec.2020': no such colour space in built-in"), std::string::npos)
        << error.what();
  }
}

const char* kScene = R"({"color_space": "sRGB", "background": [0.5, 0.5, 0.5], "ambient": [0.2, 0.2, 0.2],
  "lights": [{"type": "point", "position": [0, 1, 0], "color": [1, 0.5, 0]}],
  "materials": [{"ka": [0.1, 0.1, 0.1], "kd": [0.8, 0.2, 0.04045], "ks": [1, 1, 1], "shininess": 8}]})";

TEST(SceneColors, ConvertedFromTheSceneColorSpace) {
  Scene scene = parse_scene(kScene, "scene.json");
  EXPECT_EQ(scene.color_space, "sRGB");
  convert_scene_colors(scene, ColorConfig::builtin());
  EXPECT_TRUE(scene.color_space.empty()) << "now in the working space";
  EXPECT_NEAR(scene.background.r, srgb_decode(0.5), 1e-6);
  EXPECT_NEAR(scene.ambient.b, srgb_decode(0.2), 1e-6);
  EXPECT_NEAR(scene.lights[0].color.g, srgb_decode(0.5), 1e-6);
  EXPECT_EQ(scene.lights[0].color.r, 1.0);
  EXPECT_NEAR(scene.materials[0].kd.b, 0.04045 / 12.92, 1e-7);
  EXPECT_NEAR(scene.materials[0].ka.g, srgb_decode(0.1), 1e-6);
}

TEST(SceneColors, OutOfGamutAndUnknownSpacesAreErrors) {
  std::string text = kScene;
  text.replace(text.find("sRGB"), 4, "ACEScg");  // saturated AP1 orange has negative Rec.709 blue
  Scene scene = parse_scene(text, "scene.json");
  try {
    convert_scene_colors(scene, ColorConfig::builtin());
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("scene.json: lights[0].color [1, 0.5, 0] in 'ACEScg' is ["), std::string::npos) << message;
    EXPECT_NE(message.find("outside its gamut"), std::string::npos) << message;
  }
  text.replace(text.find("ACEScg"), 6, "Rec.2020");
  scene = parse_scene(text, "scene.json");
  EXPECT_THROW(convert_scene_colors(scene, ColorConfig::builtin()), InputError);
  EXPECT_THROW(parse_scene(R"({"color_space": ""})", "scene.json"), InputError);
}

TEST(SceneColors, TheRelighterRefusesColoursNotYetConverted) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  Scene scene = parse_scene(kScene, "scene.json");
  GBuffer gbuffer;
  gbuffer.width = gbuffer.height = 1;
  gbuffer.data_window = gbuffer.display_window = {0, 0, 0, 0};
  for (int c = 0; c < 3; ++c) gbuffer.position[c] = gbuffer.normal[c] = {c == 1 ? 1.0f : 0.0f};
  gbuffer.material = {0.0f};
  Relighter relighter{RelighterOptions{}};
  try {
    relighter.set_frame(scene, GBuffer(gbuffer));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("colours are in 'sRGB'"), std::string::npos) << error.what();
  }
  convert_scene_colors(scene, ColorConfig::builtin());
  relighter.set_frame(scene, std::move(gbuffer));
  EXPECT_EQ(relighter.shade().width, 1);
}

TEST(GBufferColors, ColourPassesAndTheBeautyConverted) {
  GBuffer gbuffer;
  gbuffer.width = 2, gbuffer.height = 1;
  const std::vector<float> encoded = {0.5f, 0.04f};
  for (int c = 0; c < 3; ++c) gbuffer.kd[c] = gbuffer.beauty[c] = encoded;
  const std::vector<float> position = {7.0f, 8.0f};
  gbuffer.position[0] = position;
  convert_gbuffer_colors(gbuffer, ColorConfig::builtin(), "sRGB");
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(gbuffer.kd[c][i], srgb_decode(encoded[i]), 1e-6);
      EXPECT_NEAR(gbuffer.beauty[c][i], srgb_decode(encoded[i]), 1e-6);
    }
  EXPECT_TRUE(gbuffer.ka[0].empty()) << "absent passes stay absent";
  EXPECT_EQ(gbuffer.position[0], position) << "positions are not colours";
}

}  // namespace
}  // namespace phongcl
