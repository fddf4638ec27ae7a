// A config written for a newer OpenColorIO than the one linked (host/color/config_downlevel.h):
// Blender 5's layout in miniature, with a built-in transform no OpenColorIO has. What this library
// can run loads and runs; what needs the missing transform, and what refers to that, is left out,
// each view named with the reason; a config that is not YAML keeps OpenColorIO's own complaint.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_runner.h"
#include "color/color_config.h"
#include "color/config_downlevel.h"
#include "color/display.h"
#include "common/error.h"
#include "image/image.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;
using testing::run_phongcl;
using testing::TempDir;

// Profile 2.5, keys OpenColorIO 2.1 does not know (interop_id), a view whose transform needs a
// built-in style no library has, a colour space and a look that refer to it through others, and a
// kept view through a LUT found on the config's search path.
constexpr const char* kNewerConfig = R"(ocio_profile_version: 2.5
search_path: luts
roles:
  scene_linear: Linear
  default: Linear
  future_role: Derived
displays:
  sRGB:
    - !<View> {name: Standard, view_transform: Plain, display_colorspace: sRGB}
    - !<View> {name: Halved, view_transform: Halving, display_colorspace: sRGB}
    - !<View> {name: Future, view_transform: Future View, display_colorspace: sRGB}
    - !<View> {name: Derived, colorspace: Derived}
    - !<View> {name: Looking, view_transform: Plain, display_colorspace: sRGB, looks: +Future Look}
active_displays: [sRGB]
active_views: [Standard, Halved, Future, Derived, Looking]
display_colorspaces:
  - !<ColorSpace>
    name: sRGB
    interop_id: srgb_rec709_display
    from_display_reference: !<ExponentTransform> {value: 2.2, direction: inverse}
view_transforms:
  - !<ViewTransform>
    name: Plain
    from_scene_reference: !<MatrixTransform> {}
  - !<ViewTransform>
    name: Halving
    from_scene_reference: !<FileTransform> {src: half.spi1d, interpolation: linear}
  - !<ViewTransform>
    name: Future View
    from_scene_reference: !<GroupTransform>
      children:
        - !<MatrixTransform> {}
        - !<BuiltinTransform> {style: NOT-IN-ANY - OpenColorIO_9.9}
colorspaces:
  - !<ColorSpace>
    name: Derived
    aliases: [derived_alias]
    from_scene_reference: !<ColorSpaceTransform> {src: Linear, dst: Future Space}
  - !<ColorSpace>
    name: Linear
    interop_id: lin_rec709_scene
  - !<ColorSpace>
    name: Future Space
    to_scene_reference: !<BuiltinTransform> {style: NOT-IN-ANY - OpenColorIO_9.9}
looks:
  - !<Look>
    name: Future Look
    process_space: derived_alias
    transform: !<MatrixTransform> {}
)";

constexpr const char* kHalvingLut = "Version 1\nFrom 0.0 1.0\nLength 2\nComponents 1\n{\n0.0\n0.5\n}\n";

fs::path write_newer_config(const TempDir& dir) {
  fs::create_directories(dir / "luts");
  std::ofstream(dir / "luts" / "half.spi1d") << kHalvingLut;
  std::ofstream(dir / "config.ocio") << kNewerConfig;
  return dir / "config.ocio";
}

std::string joined_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

TEST(ConfigDownlevel, WhatThisOpenColorIOCanRunLoadsAndEachViewLeftOutIsNamed) {
  TempDir dir;
  const ColorConfig config = ColorConfig::load(write_newer_config(dir).string());
  EXPECT_EQ(config.views("sRGB"), (std::vector<std::string>{"Standard", "Halved"}));
  const std::vector<std::string> spaces = config.color_spaces();
  EXPECT_EQ(std::count(spaces.begin(), spaces.end(), "Derived"), 0) << "it converts through Future Space";
  EXPECT_TRUE(config.looks().empty()) << "its process space is Derived's alias";
  const std::string notes = joined_lines(config.omitted());
  for (const char* view : {"Future", "Derived", "Looking"})
    EXPECT_NE(notes.find(std::string("view '") + view + "' of display 'sRGB' left out"), std::string::npos) << notes;
  EXPECT_NE(notes.find("it needs the built-in transform 'NOT-IN-ANY - OpenColorIO_9.9'"), std::string::npos) << notes;
  EXPECT_NE(notes.find("colour spaces left out, needing what OpenColorIO"), std::string::npos) << notes;
  EXPECT_NE(notes.find("1 role left out"), std::string::npos) << "future_role names Derived\n" << notes;
  EXPECT_NE(notes.find("keys ignored, unknown to OpenColorIO"), std::string::npos) << notes;
  EXPECT_NE(notes.find("interop_id"), std::string::npos) << notes;
  EXPECT_NE(config.description().find("without what it cannot run"), std::string::npos) << config.description();
}

TEST(ConfigDownlevel, KeptViewsRunTheirFilesFromTheConfigsSearchPath) {
  TempDir dir;
  const ColorConfig config = ColorConfig::load(write_newer_config(dir).string());
  Image image(2, 1);
  for (std::size_t i = 0; i < 2; ++i) {
    const float value = i == 0 ? 0.5f : 1.0f;
    float* pixel = image.pixel(i);
    pixel[0] = pixel[1] = pixel[2] = value;
    pixel[3] = 1.0f;
  }
  for (const auto& [view, factor] : {std::pair{"Standard", 1.0}, std::pair{"Halved", 0.5}}) {
    DisplaySettings settings;
    settings.view = view;
    const std::vector<std::uint8_t> bytes = DisplayTransform(config, settings).encode(image);
    for (std::size_t i = 0; i < 2; ++i) {
      const double linear = (i == 0 ? 0.5 : 1.0) * factor;
      const int expected = static_cast<int>(std::lround(255.0 * std::pow(linear, 1.0 / 2.2)));
      EXPECT_NEAR(bytes[4 * i], expected, 1) << view << " pixel " << i;  // OpenColorIO's exponent runs in float
    }
  }
}

TEST(ConfigDownlevel, AViewLeftOutIsRefusedWithTheReason) {
  TempDir dir;
  const ColorConfig config = ColorConfig::load(write_newer_config(dir).string());
  DisplaySettings settings;
  settings.view = "Future";
  try {
    DisplayTransform(config, settings);
    ADD_FAILURE() << "the view was built";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("view 'Future' of display 'sRGB' left out: it uses 'Future View'"), std::string::npos)
        << message;
  }
}

TEST(ConfigDownlevel, ConfigsThisOpenColorIOReadsAreLeftAlone) {
  EXPECT_FALSE(downlevel_config("ocio_profile_version: 2\nroles: {}\n"));
  EXPECT_FALSE(downlevel_config("ocio_profile_version: 1\n"));
  EXPECT_TRUE(ColorConfig::builtin().omitted().empty());
  EXPECT_THROW(downlevel_config("ocio_profile_version: 2.5\nroles: [unclosed\n"), std::runtime_error);
}

TEST(ConfigDownlevel, ANewerConfigThatIsNotYamlKeepsOpenColorIOsComplaint) {
  TempDir dir;
  std::ofstream(dir / "bad.ocio") << "ocio_profile_version: 2.5\nroles: [unclosed\n";
  try {
    ColorConfig::load((dir / "bad.ocio").string());
    ADD_FAILURE() << "loaded";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("bad.ocio: not a usable OCIO config"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line";
  }
}

// scripts/blender/make_root.sh lays its wrappers out as an installed Blender is (bin/blender beside
// share/blender): --blender finds the config through a link to the executable, as BLENDER does.
TEST(ConfigDownlevel, TheBlenderNamedByPathOrBlenderVariableGivesItsConfig) {
  TempDir dir;
  fs::create_directories(dir / "install" / "bin");
  fs::create_directories(dir / "install" / "share" / "blender" / "datafiles");
  const TempDir config_dir("newer_config");
  write_newer_config(config_dir);
  fs::create_directory_symlink(config_dir.path, dir / "install" / "share" / "blender" / "datafiles" / "colormanagement");
  std::ofstream(dir / "install" / "bin" / "blender") << "#!/bin/sh\nexit 0\n";
  fs::permissions(dir / "install" / "bin" / "blender", fs::perms::owner_all);
  fs::create_symlink(dir / "install" / "bin" / "blender", dir / "blender9");
  const std::string blender = (dir / "blender9").string();

  const auto named = run_phongcl("colors --ocio blender --blender '" + blender + "'");
  ASSERT_EQ(named.exit_code, 0) << named.err;
  EXPECT_NE(named.out.find("install/share/blender/datafiles/colormanagement/config.ocio"), std::string::npos) << named.out;
  EXPECT_NE(named.out.find("note       view 'Future' of display 'sRGB' left out"), std::string::npos) << named.out;
  const auto from_variable = run_phongcl("colors --ocio blender", "BLENDER='" + blender + "' ");
  ASSERT_EQ(from_variable.exit_code, 0) << from_variable.err;
  EXPECT_NE(from_variable.out.find("install/share/blender/datafiles/colormanagement/config.ocio"), std::string::npos) << from_variable.out;

  const auto absent = run_phongcl("colors --ocio blender --blender '" + (dir / "install").string() + "/none'");
  EXPECT_NE(absent.exit_code, 0);
  EXPECT_NE(absent.err.find("none: no Blender OCIO config beside it"), std::string::npos) << absent.err;
  const auto not_blender = run_phongcl("colors --ocio builtin --blender '" + blender + "'");
  EXPECT_NE(not_blender.exit_code, 0);
  EXPECT_NE(not_blender.err.find("--ocio is 'builtin'"), std::string::npos) << not_blender.err;
}

}  // namespace
}  // namespace phongcl
