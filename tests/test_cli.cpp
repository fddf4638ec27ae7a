// The phongcl commands end to end, as a user runs them: outputs, summaries, and every kind of bad
// input getting a one-line error that names the file, a non-zero exit, and no clobbered output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include <ImfFrameBuffer.h>
#include <ImfInputFile.h>
#include <ImfStandardAttributes.h>
#include <png.h>

#include <cstring>

#include "accuracy_bound.h"
#include "cli_runner.h"
#include "gbuffer/gbuffer.h"
#include "image/image.h"
#include "opencl_required.h"
#include "peers/knot_mesh.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::read_text;
using testing::run_phongcl;

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("phongcl-cli-test-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  // An existing output file that a failed run must leave exactly as it was.
  std::string existing_output() const { return write("existing.exr", "precious bytes"); }

  // A failed run: non-zero exit, one line on stderr naming `what`, nothing on the existing output.
  void expect_clean_failure(const CliRun& run, const std::string& what, const std::string& output) const {
    EXPECT_NE(run.exit_code, 0) << run.out << run.err;
    EXPECT_NE(run.err.find(what), std::string::npos) << "stderr: " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << "stderr should be one line: " << run.err;
    EXPECT_EQ(read_text(output), "precious bytes");
    for (const auto& entry : fs::directory_iterator(dir_)) {
      EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "temporary left behind: " << entry.path();
    }
  }

  fs::path dir_;
};

constexpr const char* kDefaultScene = "scenes/default/scene.json";

TEST_F(Cli, ShadeWritesImagesAndSaysWhatItDid) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const CliRun run = run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + path("lit.exr") +
                                 " --png " + path("lit.png") + " --explain");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* expected : {"640 x 480", "307,200 pixels", "2 point + 1 directional", "device", "kernel",
                               "Mpixels/s", "build options", "-DSPECULAR", "wrote"}) {
    EXPECT_NE(run.out.find(expected), std::string::npos) << "missing '" << expected << "' in:\n" << run.out;
  }
  EXPECT_GT(fs::file_size(path("lit.exr")), 1000u);
  EXPECT_EQ(read_text(path("lit.png")).substr(1, 3), "PNG");
}

TEST_F(Cli, ShadeMatchesReferenceThroughCompare) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const std::string scene = " --scene scenes/shininess/scene.json";
  ASSERT_EQ(run_phongcl("shade" + scene + " --out " + path("lit.exr")).exit_code, 0);
  ASSERT_EQ(run_phongcl("reference" + scene + " --out " + path("ref.exr")).exit_code, 0);
  std::ostringstream bound;  // the product's bound, measured as tests/accuracy_bound.h states it
  bound << " --tolerance " << testing::kRelativeBound << " --abs-floor " << testing::kErrorFloor;
  const CliRun compare = run_phongcl("compare " + path("lit.exr") + " " + path("ref.exr") + bound.str());
  EXPECT_EQ(compare.exit_code, 0) << compare.out << compare.err;
  for (const char* expected : {"max abs", "max rel", "RMSE", "PSNR", "worst"}) {
    EXPECT_NE(compare.out.find(expected), std::string::npos) << compare.out;
  }
}

// The reference's --aov holds each term as shade's does: the same layers, within the product's bound.
TEST_F(Cli, ReferenceAovHoldsTheTermsShadesDoes) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const std::string scene = " --scene scenes/shininess/scene.json";
  ASSERT_EQ(run_phongcl("shade" + scene + " --aov " + path("lit.aov.exr")).exit_code, 0);
  const CliRun reference = run_phongcl("reference" + scene + " --aov " + path("ref.aov.exr"));
  ASSERT_EQ(reference.exit_code, 0) << reference.err;
  auto read_layer = [&](const std::string& file, const std::string& layer) {
    Imf::InputFile in(path(file).c_str());
    const Imath::Box2i window = in.header().dataWindow();
    const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    std::vector<float> values(3 * static_cast<std::size_t>(width) * height);
    Imf::FrameBuffer buffer;
    for (int c = 0; c < 3; ++c)
      buffer.insert(layer + "." + "RGB"[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data() + c) -
                                                           (window.min.x + std::ptrdiff_t{window.min.y} * width) * 3 * sizeof(float),
                                                       3 * sizeof(float), 3 * sizeof(float) * width));
    in.setFrameBuffer(buffer);
    in.readPixels(window.min.y, window.max.y);
    return values;
  };
  for (const char* layer : {"ambient", "diffuse", "specular"}) {
    const std::vector<float> got = read_layer("lit.aov.exr", layer), want = read_layer("ref.aov.exr", layer);
    ASSERT_EQ(got.size(), want.size()) << layer;
    const double largest = *std::max_element(want.begin(), want.end());
    EXPECT_GT(largest, 0.0) << layer << ": the reference's layer is empty";
    // A term alone has faint pixels that the image's sum does not: its floor is 1e-4 of its largest.
    const double floor = std::max(testing::kErrorFloor, 1e-4 * largest);
    double worst = 0.0;
    for (std::size_t i = 0; i < got.size(); ++i)
      worst = std::max(worst, std::abs(double(got[i]) - want[i]) / std::max(std::abs(double(want[i])), floor));
    // Measured 1.0e-3 on the specular layer (scenes/shininess's exponents up to 1024, float's pow),
    // which the whole image's bound meets only with the diffuse beside it.
    EXPECT_LE(worst, 4 * testing::kRelativeBound) << layer;
  }
}

TEST_F(Cli, GbufferCommandWritesALoadableGBuffer) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  ASSERT_EQ(run_phongcl(std::string("gbuffer --scene ") + kDefaultScene + " --out " + path("g.exr")).exit_code, 0);
  const CliRun run = run_phongcl(std::string("shade --scene ") + kDefaultScene + " --gbuffer " + path("g.exr") +
                                 " --out " + path("lit.exr"));
  EXPECT_EQ(run.exit_code, 0) << run.err;
}

TEST_F(Cli, SecondRunHitsTheProgramCache) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const std::string env = "PHONGCL_CACHE_DIR='" + path("cache") + "' ";
  const std::string args = std::string("shade --scene ") + kDefaultScene + " --out " + path("lit.exr");
  const CliRun first = run_phongcl(args, env);
  const CliRun second = run_phongcl(args, env);
  EXPECT_NE(first.out.find("compiled"), std::string::npos) << first.out;
  EXPECT_NE(second.out.find("cache hit (disk)"), std::string::npos) << second.out;
}

TEST_F(Cli, WorksWithoutAHomeDirectory) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const CliRun run = run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + path("lit.exr"),
                                 "env -u HOME -u XDG_CACHE_HOME -u PHONGCL_CACHE_DIR -u POCL_CACHE_DIR ");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("no disk cache"), std::string::npos) << run.out;
}

TEST_F(Cli, TruncatedGBufferFailsCleanly) {
  const std::string full = read_text(fs::path(PHONGCL_SOURCE_DIR) / "scenes/default/gbuffer.exr");
  const std::string truncated = write("truncated.exr", full.substr(0, full.size() / 2));
  const std::string out = existing_output();
  const CliRun run = run_phongcl(std::string("shade --scene ") + kDefaultScene + " --gbuffer " + truncated + " --out " + out);
  expect_clean_failure(run, "truncated.exr", out);
}

TEST_F(Cli, NotAnExrFailsCleanly) {
  const std::string bogus = write("bogus.exr", "this is not an OpenEXR file\n");
  const std::string out = existing_output();
  expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --gbuffer " + bogus + " --out " + out),
                       "bogus.exr", out);
}

TEST_F(Cli, BadScenesFailCleanly) {
  const std::string out = existing_output();
  const std::string gbuffer = std::string(" --gbuffer ") + PHONGCL_SOURCE_DIR + "/scenes/default/gbuffer.exr --out " + out;
  const std::string base_lights = R"("lights": [{"type": "point", "position": [1, 2, 3], "color": [1, 1, 1]}])";
  const std::string material = R"({"ka": [0.1, 0.1, 0.1], "kd": [0.5, 0.5, 0.5], "ks": [0, 0, 0], "shininess": 4})";
  const std::string materials = "\"materials\": [" + material + ", " + material + ", " + material + ", " + material +
                                ", " + material + "]";
  struct Case {
    const char* name;
    std::string json;
    const char* expected;
  };
  const Case cases[] = {
      {"syntax", R"({"camera": {"eye": [0, 1, 6]},)", "syntax.json"},
      {"unknown_key", R"({"camera": {"eye": [0, 1, 6]}, "colour": 1})", "colour"},
      {"light_type", R"({"camera": {"eye": [0, 1, 6]}, "lights": [{"type": "mesh", "position": [0, 0, 0]}]})", "mesh"},
      {"shininess", "{\"camera\": {\"eye\": [0, 1, 6]}, " + base_lights +
                        R"(, "materials": [{"ka": [0,0,0], "kd": [1,1,1], "ks": [1,1,1], "shininess": -3}]})",
       "shininess"},
      {"too_few_materials", "{\"camera\": {\"eye\": [0, 1, 6]}, " + base_lights +
                                R"(, "materials": [{"ka": [0,0,0], "kd": [1,1,1], "ks": [1,1,1], "shininess": 3}]})",
       "out of range"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string scene = write(std::string(c.name) + ".json", c.json);
    expect_clean_failure(run_phongcl("shade --scene " + scene + gbuffer), c.expected, out);
  }
  // A valid scene with enough materials shades (so the failures above are about what they say).
  if (testing::have_opencl_device()) {
    const std::string good = write("good.json", "{\"camera\": {\"eye\": [0, 1, 6]}, " + base_lights + ", " + materials + "}");
    const CliRun run = run_phongcl("shade --scene " + good + " --gbuffer " + PHONGCL_SOURCE_DIR +
                                   "/scenes/default/gbuffer.exr --out " + path("good.exr"));
    EXPECT_EQ(run.exit_code, 0) << run.err;
  }
}

TEST_F(Cli, MissingGBufferFailsCleanly) {
  const std::string out = existing_output();
  const std::string scene = write("no_gbuffer.json", R"({"camera": {"eye": [0, 1, 6]}})");
  expect_clean_failure(run_phongcl("shade --scene " + scene + " --out " + out), "no G-buffer", out);
  expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --gbuffer " + path("absent.exr") +
                                   " --out " + out),
                       "absent.exr", out);
}

TEST_F(Cli, NoOpenCLDeviceIsAClearError) {
  const std::string out = existing_output();
  // The ICD loader reads vendors from OCL_ICD_VENDORS: an empty directory means no platform at all.
  fs::create_directories(path("no-vendors"));
  const CliRun run = run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out,
                                 "OCL_ICD_VENDORS='" + path("no-vendors") + "' ");
  expect_clean_failure(run, "no OpenCL device", out);
}

TEST_F(Cli, KernelBuildFailureShowsTheBuildLog) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const fs::path kernels = fs::path(PHONGCL_SOURCE_DIR) / "kernels";
  fs::create_directories(path("kernels"));
  for (const auto& entry : fs::directory_iterator(kernels)) fs::copy(entry.path(), path("kernels"));
  std::ofstream(path("kernels/phong.cl"), std::ios::app) << "\nthis_is_not_opencl_c;\n";
  const std::string out = existing_output();
  const CliRun run = run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out,
                                 "PHONGCL_KERNEL_DIR='" + path("kernels") + "' PHONGCL_CACHE_DIR='" + path("cache") + "' ");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("kernel build failed"), std::string::npos) << run.err;
  // The log points at the broken line of the original file (the #line directives keep it so).
  const std::string kernel_text = read_text(path("kernels/phong.cl"));
  const std::string broken_line = "phong.cl:" + std::to_string(std::count(kernel_text.begin(), kernel_text.end(), '\n'));
  EXPECT_NE(run.err.find(broken_line), std::string::npos) << "build log should name " << broken_line << ": " << run.err;
  EXPECT_EQ(read_text(out), "precious bytes");
}

TEST_F(Cli, UnwritableOutputDirectoryFailsCleanly) {
  const std::string out = existing_output();
  expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + path("missing-dir/lit.exr")),
                       "missing-dir", out);
  EXPECT_FALSE(fs::exists(path("missing-dir")));
  // A PNG or AOV that cannot be written must not cost the existing --out.
  expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out + " --png " +
                                   path("missing-dir/lit.png")),
                       "lit.png", out);
  expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out + " --aov " +
                                   path("missing-dir/terms.exr")),
                       "terms.exr", out);
}

TEST_F(Cli, BadFlagsAreOneLineErrors) {
  const std::string out = existing_output();
  expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out + " --precision bogus"),
                       "--precision", out);
  expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out +
                                   " --device 99999999999999999999"),
                       "--device", out);
  // The Relighter's own check (check_options), which the Python module meets too.
  expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out + " --lanes 3"),
                       "lanes must be 0 (the device's choice), 1, 2, 4, 8 or 16 (got 3)", out);
}

TEST_F(Cli, LanesAreWhatWasAskedFor) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const CliRun run =
      run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + path("lit.exr") + " --lanes 4 --explain");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("lanes: 4 pixels per work-item (as asked)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("-DPHONGCL_LANES=4"), std::string::npos) << run.out;
}

TEST_F(Cli, NonFinitePixelsAreCountedNotFatal) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  GBuffer gbuffer = read_gbuffer(fs::path(PHONGCL_SOURCE_DIR) / "scenes/default/gbuffer.exr");
  std::size_t shaded = 0;
  for (std::size_t i = 0; i < gbuffer.pixel_count() && shaded < 3; ++i) {
    if (classify_pixel(gbuffer, i) != PixelClass::shaded) continue;
    gbuffer.normal[shaded][i] = std::numeric_limits<float>::quiet_NaN();  // three pixels, one axis each
    ++shaded;
  }
  write_gbuffer(gbuffer, path("nan.exr"));
  const CliRun run = run_phongcl(std::string("shade --scene ") + kDefaultScene + " --gbuffer " + path("nan.exr") +
                                 " --out " + path("lit.exr"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("3 pixels had non-finite normals and were left unshaded"), std::string::npos) << run.out;
  EXPECT_TRUE(fs::exists(path("lit.exr")));
}

// ---- Colour: OCIO configs, display options, what EXRs and PNGs hold ----

std::vector<std::uint8_t> png_rgba(const std::string& file) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, file.c_str())) return {};
  png.format = PNG_FORMAT_RGBA;
  std::vector<std::uint8_t> bytes(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr)) return {};
  return bytes;
}

TEST_F(Cli, ColorsListsWhatAConfigOffers) {
  const CliRun run = run_phongcl("colors");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* expected : {"built-in", "Linear Rec.709 (sRGB) (scene_linear)", "R (0.6400, 0.3300)",
                               "sRGB (default): views reinhard, aces, clamp (default reinhard)", "looks      none",
                               "ACEScg", "pipeline   reinhard: compiled: per-channel table"}) {
    EXPECT_NE(run.out.find(expected), std::string::npos) << "missing '" << expected << "' in:\n" << run.out;
  }
  const std::string out = existing_output();
  const CliRun bad = run_phongcl("colors --ocio " + path("absent.ocio"));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("absent.ocio: cannot read the OCIO config"), std::string::npos) << bad.err;
}

// A view whose LUT is missing is listed with its reason, the views after it still are, and the
// command fails after the listing (it stopped at the broken view).
TEST_F(Cli, ColorsListsEveryViewAndFailsOnOneThatCannotBeBuilt) {
  const std::string config = write("broken.ocio", R"(ocio_profile_version: 2
search_path: luts
roles:
  default: raw
  scene_linear: raw
file_rules:
  - !<Rule> {name: Default, colorspace: raw}
displays:
  sRGB:
    - !<View> {name: Raw, colorspace: raw}
    - !<View> {name: Broken, colorspace: lut}
    - !<View> {name: After, colorspace: raw}
colorspaces:
  - !<ColorSpace>
    name: raw
  - !<ColorSpace>
    name: lut
    from_scene_reference: !<FileTransform> {src: missing.spi1d}
)");
  const CliRun run = run_phongcl("colors --ocio " + config);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("pipeline   Broken: cannot be built: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("missing.spi1d"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("pipeline   After: compiled"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("broken.ocio: the views Broken cannot be built (listed above)\n"), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
}

TEST_F(Cli, DisplayNamesAreCheckedBeforeShading) {
  const std::string out = existing_output();
  const std::string shade = std::string("shade --scene ") + kDefaultScene + " --out " + out + " --png " + path("lit.png");
  expect_clean_failure(run_phongcl(shade + " --view Filmic"), "has no view 'Filmic' (views: reinhard, aces, clamp)", out);
  expect_clean_failure(run_phongcl(shade + " --look 'High Contrast'"), "no look 'High Contrast'", out);
  expect_clean_failure(run_phongcl(shade + " --tonemap aces --view aces"), "--tonemap", out);
  expect_clean_failure(run_phongcl(shade + " --ocio " + path("absent.ocio")), "absent.ocio", out);
  EXPECT_FALSE(fs::exists(path("lit.png")));
}

TEST_F(Cli, ExrsAreBlackWhereTransparentUnlessAsked) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const std::string shade = std::string("shade --scene ") + kDefaultScene;
  ASSERT_EQ(run_phongcl(shade + " --out " + path("lit.exr") + " --png " + path("lit.png")).exit_code, 0);
  ASSERT_EQ(run_phongcl(shade + " --out " + path("old.exr") + " --exr-background").exit_code, 0);
  const Image lit = read_exr(path("lit.exr")), old = read_exr(path("old.exr"));
  const std::vector<std::uint8_t> png = png_rgba(path("lit.png"));
  ASSERT_EQ(png.size(), 4 * lit.pixel_count());
  std::size_t sky = 0;
  for (std::size_t i = 0; i < lit.pixel_count(); ++i) {
    if (lit.pixel(i)[3] != 0.0f) continue;
    ++sky;
    const float expected_old[] = {0.05f, 0.06f, 0.1f};  // scenes/default's background
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(lit.pixel(i)[c], 0.0f) << "pixel " << i << ": premultiplied, nothing to add to the plate";
      ASSERT_EQ(old.pixel(i)[c], expected_old[c]) << "pixel " << i << ": --exr-background keeps the old colour";
    }
    // The preview shows the background there (reinhard of 0.05, 0.06, 0.1 in sRGB), opaque.
    ASSERT_EQ(png[4 * i], 62);  // 61.64
    ASSERT_EQ(png[4 * i + 1], 67);  // 67.29
    ASSERT_EQ(png[4 * i + 2], 85);  // 85.03
    ASSERT_EQ(png[4 * i + 3], 255);
  }
  EXPECT_GT(sky, 10000u);
  const Imf::Header header = Imf::InputFile(path("lit.exr").c_str()).header();
  ASSERT_TRUE(Imf::hasChromaticities(header)) << "the working space's primaries";
  EXPECT_NEAR(Imf::chromaticities(header).red.x, 0.64f, 1e-4);
}

TEST_F(Cli, PngOfAnExrIsShadesOwnPreview) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  ASSERT_EQ(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + path("lit.exr") + " --png " +
                        path("shade.png") + " --view aces --exposure 0.5")
                .exit_code,
            0);
  const CliRun png = run_phongcl("png " + path("lit.exr") + " " + path("png.png") +
                                 " --tonemap aces --exposure 0.5 --background 0.05 0.06 0.1");
  ASSERT_EQ(png.exit_code, 0) << png.err;
  EXPECT_NE(png.out.find("640 x 480, sRGB, aces"), std::string::npos) << png.out;
  EXPECT_EQ(png_rgba(path("png.png")), png_rgba(path("shade.png")));
  const std::string exr = read_text(path("lit.exr"));
  const CliRun onto_itself = run_phongcl("png " + path("lit.exr") + " " + path("lit.exr"));
  EXPECT_NE(onto_itself.exit_code, 0);
  EXPECT_NE(onto_itself.err.find("output '" + path("lit.exr") + "' and input '" + path("lit.exr") + "' are the same file"),
            std::string::npos)
      << onto_itself.err;
  EXPECT_EQ(read_text(path("lit.exr")), exr);
}

TEST_F(Cli, GbufferSpaceConvertsTheColourPasses) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const std::string shade = "shade --scene tests/fixtures/blender/scene.json --gbuffer tests/fixtures/blender/cycles.exr";
  ASSERT_EQ(run_phongcl(shade + " --out " + path("linear.exr")).exit_code, 0);
  const CliRun run = run_phongcl(shade + " --out " + path("srgb.exr") + " --gbuffer-space sRGB");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("colour passes from sRGB to Linear Rec.709 (sRGB)"), std::string::npos) << run.out;
  // DiffCol read as sRGB-encoded is darker in linear terms: kd (and the diffuse light) drops.
  const Image linear = read_exr(path("linear.exr")), srgb = read_exr(path("srgb.exr"));
  double linear_sum = 0, srgb_sum = 0;
  for (std::size_t i = 0; i < linear.rgba.size(); ++i) linear_sum += linear.rgba[i], srgb_sum += srgb.rgba[i];
  EXPECT_LT(srgb_sum, 0.9 * linear_sum);
  const std::string out = existing_output();
  expect_clean_failure(run_phongcl(shade + " --out " + out + " --gbuffer-space Rec.2020"),
                       "--gbuffer-space 'Rec.2020': no such colour space", out);
}

TEST_F(Cli, SceneColoursNameTheirSpace) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  // The same scene twice: colours as sRGB-encoded values, and the same colours decoded by hand.
  const std::string gbuffer = " --gbuffer scenes/default/gbuffer.exr";
  const std::string encoded = write("encoded.json", R"({"color_space": "sRGB", "camera": {"eye": [0, 2, 8], "look_at": [0, 0.7, 0]},
    "lights": [{"type": "point", "position": [4, 6, 5], "color": [1, 0.5, 0.25]}],
    "materials": [{"kd": [0.5, 0.5, 0.5], "ks": [0, 0, 0]}, {"kd": [0.8, 0.1, 0.1], "ks": [0, 0, 0]}, {"kd": [0.2, 0.6, 0.2]},
                  {"kd": [0.1, 0.2, 0.8]}, {"kd": [0.7, 0.6, 0.2]}]})");
  const auto decode = [](double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); };
  std::string decoded_text = R"({"camera": {"eye": [0, 2, 8], "look_at": [0, 0.7, 0]},
    "lights": [{"type": "point", "position": [4, 6, 5], "color": [1, L5, L25]}],
    "materials": [{"kd": [M5, M5, M5], "ks": [0, 0, 0]}, {"kd": [M8, M1, M1], "ks": [0, 0, 0]}, {"kd": [M2, M6, M2]},
                  {"kd": [M1, M2, M8]}, {"kd": [M7, M6, M2]}]})";
  for (const auto& [key, v] : std::vector<std::pair<std::string, double>>{
           {"L25", 0.25}, {"L5", 0.5}, {"M5", 0.5}, {"M8", 0.8}, {"M1", 0.1}, {"M2", 0.2}, {"M6", 0.6}, {"M7", 0.7}})
    for (std::size_t at; (at = decoded_text.find(key)) != std::string::npos;) decoded_text.replace(at, key.size(), std::to_string(decode(v)));
  const std::string decoded = write("decoded.json", decoded_text);
  ASSERT_EQ(run_phongcl("shade --scene " + encoded + gbuffer + " --out " + path("a.exr")).exit_code, 0);
  ASSERT_EQ(run_phongcl("shade --scene " + decoded + gbuffer + " --out " + path("b.exr")).exit_code, 0);
  const Image a = read_exr(path("a.exr")), b = read_exr(path("b.exr"));
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    ASSERT_NEAR(a.rgba[i], b.rgba[i], 1e-5 + 1e-5 * std::abs(b.rgba[i])) << "value " << i;  // std::to_string's 6 decimals
}

// An output that names an input, or another output, is refused before anything is read: one line
// naming both options, every file as it was. Names are compared resolved (symbolic links, "..")
// and, for files that exist, by device and inode (hard links).
TEST_F(Cli, OutputsThatAreInputsAreRefusedBeforeAnythingIsRead) {
  const fs::path source = fs::path(PHONGCL_SOURCE_DIR) / "scenes/default";
  fs::copy_file(source / "scene.json", path("scene.json"));
  fs::copy_file(source / "gbuffer.exr", path("gbuffer.exr"));
  fs::create_directories(path("sub"));
  fs::create_hard_link(path("gbuffer.exr"), path("linked.exr"));
  fs::create_symlink(path("gbuffer.exr"), path("pointer.exr"));
  const std::string gbuffer_bytes = read_text(path("gbuffer.exr")), scene_bytes = read_text(path("scene.json"));
  const std::string out = existing_output();
  const std::string shade = "shade --scene " + path("scene.json");
  struct Case {
    std::string arguments;
    std::string says;
  };
  const Case cases[] = {
      {" --gbuffer " + path("gbuffer.exr") + " --out " + path("gbuffer.exr"), "--out '" + path("gbuffer.exr") + "' and --gbuffer"},
      {" --out " + path("scene.json"), "--out '" + path("scene.json") + "' and --scene"},
      {" --out " + path("gbuffer.exr"), "and the scene's \"gbuffer\" entry"},
      {" --out " + path("sub/../gbuffer.exr"), "and the scene's \"gbuffer\" entry"},
      {" --out " + path("linked.exr"), "and the scene's \"gbuffer\" entry"},
      {" --out " + path("pointer.exr"), "and the scene's \"gbuffer\" entry"},
      {" --out " + out + " --png " + path("gbuffer.exr"), "--png"},
      {" --out " + path("x.exr") + " --aov " + path("x.exr"), "two outputs cannot share a file"},
      {" --out " + path("x.exr") + " --png " + path("x.exr"), "two outputs cannot share a file"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.arguments);
    expect_clean_failure(run_phongcl(shade + c.arguments), c.says, out);
    EXPECT_EQ(read_text(path("gbuffer.exr")), gbuffer_bytes);
    EXPECT_EQ(read_text(path("scene.json")), scene_bytes);
    EXPECT_FALSE(fs::exists(path("x.exr")));
  }
}

// The meshes a scene's objects name (here under a transform) are inputs too: no output may replace
// one, whether the G-buffer comes from the scene or from --gbuffer, and gbuffer --out neither.
TEST_F(Cli, OutputsOverTheScenesMeshesAreRefused) {
  const fs::path source = fs::path(PHONGCL_SOURCE_DIR) / "scenes/default";
  fs::copy_file(source / "gbuffer.exr", path("gbuffer.exr"));
  std::string scene = read_text(source / "scene.json");
  const std::string objects = "\"objects\": [";
  scene.insert(scene.find(objects) + objects.size(),
               R"({"type": "transform", "translate": [0, 3, 0], "children": [{"type": "mesh", "file": "rock.ply", "material": 1}]}, )");
  write_ply(path("knot.ply"), trefoil_knot(8, 4));
  const std::string mesh_bytes = read_text(path("knot.ply"));
  const std::string out = path("existing.exr");
  const std::string mesh = "the scene's mesh '" + path("rock.ply") + "'";
  struct Case {
    std::string arguments;
    std::string says;
  };
  const std::string shade = "shade --scene " + path("scene.json");
  const Case cases[] = {
      {shade + " --out " + path("rock.ply"), "--out '" + path("rock.ply") + "' and " + mesh},
      {shade + " --gbuffer " + path("gbuffer.exr") + " --out " + path("rock.ply"), "--out '" + path("rock.ply") + "' and " + mesh},
      {shade + " --out " + out + " --png " + path("rock.ply"), "--png '" + path("rock.ply") + "' and " + mesh},
      {shade + " --out " + out + " --aov " + path("rock.ply"), "--aov '" + path("rock.ply") + "' and " + mesh},
      {"gbuffer --scene " + path("scene.json") + " --out " + path("rock.ply"), "--out '" + path("rock.ply") + "' and " + mesh},
      {"gbuffer --scene " + path("scene.json") + " --out " + path("scene.json"), "--out '" + path("scene.json") + "' and --scene"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.arguments);
    write("scene.json", scene);
    write("rock.ply", mesh_bytes);
    existing_output();
    expect_clean_failure(run_phongcl(c.arguments), c.says, out);
    EXPECT_TRUE(read_text(path("rock.ply")) == mesh_bytes) << "the mesh was replaced";
    EXPECT_EQ(read_text(path("scene.json")), scene);
  }
}

// Sequences compare the file of every requested frame, in either spelling of the pattern.
TEST_F(Cli, SequenceOutputsThatAreInputFramesAreRefused) {
  const fs::path source = fs::path(PHONGCL_SOURCE_DIR) / "scenes/default";
  fs::create_directories(path("in"));
  for (const char* frame : {"1001", "1002"}) fs::copy_file(source / "gbuffer.exr", path(std::string("in/shot.") + frame + ".exr"));
  const std::string frame_bytes = read_text(path("in/shot.1002.exr"));
  const std::string out = existing_output();
  const std::string shade = "shade --scene " + (source / "scene.json").string() + " --gbuffer " + path("in/shot.####.exr");
  const std::string cases[] = {
      " --out " + path("lit.####.exr") + " --png " + path("in/shot.####.exr"),
      " --out " + path("in/shot.%04d.exr") + " --overwrite",
      " --out " + path("in/shot.####.exr"),
  };
  for (const std::string& arguments : cases) {
    SCOPED_TRACE(arguments);
    const CliRun run = run_phongcl(shade + arguments);
    expect_clean_failure(run, "'" + path("in/shot.####.exr") + "' (" + path("in/shot.1001.exr") + ") are the same file", out);
    EXPECT_EQ(read_text(path("in/shot.1002.exr")), frame_bytes);
  }
}

TEST_F(Cli, ExposureIsCheckedBeforeShading) {
  const std::string out = existing_output();
  for (const char* exposure : {"nan", "inf", "1e308", "-1000"}) {
    SCOPED_TRACE(exposure);
    expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out + " --png " +
                                     path("lit.png") + " --exposure " + exposure),
                         "--exposure: exposure must be a finite number of stops in [-40, 40]", out);
    EXPECT_FALSE(fs::exists(path("lit.png")));
  }
}

// The temporary beside an output is named after it: a name that fits its file system must give a
// temporary that fits too, and one that does not is refused before shading.
TEST_F(Cli, LongOutputNamesWriteAndTooLongOnesAreRefusedUpFront) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const std::string longest = path(std::string(251, 'n') + ".exr");  // 255 bytes
  const CliRun run = run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + longest);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(longest));
  const std::string out = existing_output();
  expect_clean_failure(run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out + " --png " +
                                   path(std::string(253, 'n') + ".png")),
                       "the file name is 257 bytes, longer than the 255 its file system allows", out);
}

// A write that runs out of space (here: a file size limit, as a full disk fails it) names the
// output, not the unnamed temporary's /proc/self/fd/N.
TEST_F(Cli, AFailedWriteNamesTheOutput) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  const std::string out = path("big.exr");
  const CliRun run = run_phongcl(std::string("shade --scene ") + kDefaultScene + " --out " + out + " --compression none",
                                 "trap '' XFSZ; ulimit -f 1024; ");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find(out + ": cannot write EXR"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("/proc/self/fd"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(dir_)) ADD_FAILURE() << "left behind: " << entry.path();
}

}  // namespace
}  // namespace phongcl
