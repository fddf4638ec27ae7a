// Real renderers' G-buffers: files written here with OpenEXR's own API under the exact channel
// names Blender and Arnold/RenderMan-style AOV outputs use, read back into the same G-buffer as the
// native layout; multi-part files, every compression, offset data windows; positions rebuilt from
// depth; camera space; the AOV output; and the CLI end to end.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfTiledOutputFile.h>
#include <ImfTiledOutputPart.h>
#include <half.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "common/error.h"
#include "gbuffer/layouts.h"
#include "raycast/depth_reconstruction.h"
#include "raycast/raycast.h"
#include "scene/camera_space.h"
#include "shading_support.h"

#include "temp_dir.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, removed afterwards.
struct TempDir : testing::TempDir {
  TempDir() : testing::TempDir("layouts") {}
};

const fs::path kSourceDir = PHONGCL_SOURCE_DIR;
const fs::path kDefaultScene = kSourceDir / "scenes/default/scene.json";

// The default scene at a small size (odd, so no block or tile size divides it) and its G-buffer.
struct Fixture {
  Scene scene;
  GBuffer native;
};
Fixture default_scene(int width = 97, int height = 61) {
  Scene scene = load_scene(kDefaultScene);
  scene.camera.width = width;
  scene.camera.height = height;
  return {scene, generate_gbuffer(scene)};
}

bool shaded(const GBuffer& g, std::size_t i) { return g.material[i] >= 0.0f; }

// A per-pixel colour plane from the material table (0 on background), as a renderer's colour pass.
Planes3 table_colors(const Scene& scene, const GBuffer& g, glm::dvec3 Material::*color) {
  Planes3 planes;
  for (int c = 0; c < 3; ++c) {
    planes[c].assign(g.pixel_count(), 0.0f);
    for (std::size_t i = 0; i < g.pixel_count(); ++i)
      if (shaded(g, i)) planes[c][i] = static_cast<float>((scene.materials[static_cast<std::size_t>(g.material[i])].*color)[c]);
  }
  return planes;
}

// One EXR channel and its values (a plane of the G-buffer's data window).
struct Channel {
  std::string name;
  Plane values;
};
using Channels = std::vector<Channel>;

void add3(Channels& channels, const std::string& base, const char* suffixes, const Planes3& planes) {
  for (int c = 0; c < 3; ++c) channels.push_back({base + "." + suffixes[c], planes[c]});
}

Plane material_index_pass(const GBuffer& g) {  // renderers write 0, not -1, where nothing was hit
  Plane index = g.material;
  for (float& value : index) value = std::max(value, 0.0f);
  return index;
}

Plane alpha_pass(const GBuffer& g) {
  Plane alpha(g.pixel_count());
  for (std::size_t i = 0; i < alpha.size(); ++i) alpha[i] = shaded(g, i) ? 1.0f : 0.0f;
  return alpha;
}

enum class DepthPass { none, distance, view_z };

Plane depth_pass(const Scene& scene, const GBuffer& g, DepthPass kind) {
  const glm::dvec3 eye = scene.camera.eye, forward = glm::normalize(scene.camera.look_at - scene.camera.eye);
  Plane depth(g.pixel_count(), 1e10f);  // Blender's "nothing here"
  for (std::size_t i = 0; i < depth.size(); ++i) {
    if (!shaded(g, i)) continue;
    const glm::dvec3 offset = glm::dvec3(g.position[0][i], g.position[1][i], g.position[2][i]) - eye;
    depth[i] = static_cast<float>(kind == DepthPass::distance ? glm::length(offset) : glm::dot(offset, forward));
  }
  return depth;
}

// Blender's multilayer EXR: "<layer>.<pass>.<channel>", short (2.7x-3.x) or long (4.x) pass names.
struct BlenderStyle {
  std::string layer = "ViewLayer";
  bool long_names = false;
  bool position = true;
  DepthPass depth = DepthPass::none;
  bool colors = true;
};
Channels blender_channels(const Scene& scene, const GBuffer& g, const BlenderStyle& style) {
  const std::string p = style.layer + ".";
  Channels channels;
  if (style.position) add3(channels, p + "Position", "XYZ", g.position);
  add3(channels, p + "Normal", "XYZ", g.normal);
  if (style.depth != DepthPass::none) channels.push_back({p + "Depth.Z", depth_pass(scene, g, style.depth)});
  channels.push_back({p + (style.long_names ? "Material Index.X" : "IndexMA.X"), material_index_pass(g)});
  if (style.colors) {
    add3(channels, p + (style.long_names ? "Diffuse Color" : "DiffCol"), "RGB", table_colors(scene, g, &Material::kd));
    add3(channels, p + (style.long_names ? "Glossy Color" : "GlossCol"), "RGB", table_colors(scene, g, &Material::ks));
  }
  channels.push_back({p + "Combined.A", alpha_pass(g)});
  for (const char* rgb : {"R", "G", "B"}) channels.push_back({p + "Combined." + rgb, Plane(g.pixel_count(), 0.5f)});
  return channels;
}

// Both colour passes used, as the aov layout does by default.
ReadOptions colour_passes() {
  ReadOptions options;
  options.kd = options.ks = ColourSource::pass;
  return options;
}

ReadOptions with_layout(Layout layout, const std::string& view_layer = "") {
  ReadOptions options;
  options.layout = layout;
  options.view_layer = view_layer;
  return options;
}

// What reading a Blender file must give: the native buffer plus per-pixel kd and ks.
GBuffer with_table_colors(const Scene& scene, GBuffer g) {
  g.kd = table_colors(scene, g, &Material::kd);
  g.ks = table_colors(scene, g, &Material::ks);
  return g;
}

struct FileFormat {
  Imf::Compression compression = Imf::ZIP_COMPRESSION;
  Imf::PixelType type = Imf::FLOAT;
  bool tiled = false;
};

std::string compression_name(Imf::Compression compression) {
  static const char* const kNames[] = {"NO", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB"};
  return kNames[compression];
}

Imf::Header header_for(const GBuffer& g, const FileFormat& format) {
  const auto box = [](const PixelWindow& w) { return Imath::Box2i({w.x_min, w.y_min}, {w.x_max, w.y_max}); };
  Imf::Header header(box(g.display_window), box(g.data_window));
  header.compression() = format.compression;
  if (format.tiled) header.setTileDescription(Imf::TileDescription(16, 16, Imf::ONE_LEVEL));
  return header;
}

// Frame buffer over `channels` (converted to half where asked: OpenEXR converts on reading only).
struct Pixels {
  Imf::FrameBuffer frame_buffer;
  std::vector<std::vector<half>> half_planes;
};
void describe_channels(Imf::Header& header, Pixels& pixels, const Channels& channels, Imf::PixelType type, const std::string& strip_prefix = "") {
  const Imath::Box2i window = header.dataWindow();
  pixels.half_planes.reserve(pixels.half_planes.size() + channels.size());
  for (const auto& channel : channels) {
    const std::string name = channel.name.substr(strip_prefix.size());
    header.channels().insert(name, Imf::Channel(type));
    if (type == Imf::FLOAT) {
      pixels.frame_buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, channel.values.data(), window));
      continue;
    }
    auto& plane = pixels.half_planes.emplace_back(channel.values.begin(), channel.values.end());
    pixels.frame_buffer.insert(name, Imf::Slice::Make(Imf::HALF, plane.data(), window));
  }
}

void write_file(const fs::path& file, const GBuffer& g, const Channels& channels, const FileFormat& format = {}) {
  Imf::Header header = header_for(g, format);
  Pixels pixels;
  describe_channels(header, pixels, channels, format.type);
  if (format.tiled) {
    Imf::TiledOutputFile out(file.c_str(), header);
    out.setFrameBuffer(pixels.frame_buffer);
    out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
  } else {
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(pixels.frame_buffer);
    out.writePixels(g.height);
  }
}

// One part per entry: its name and channels; with strip_prefix the part name is left off the
// channel names (as Nuke writes layers), else channels keep their full names.
struct Part {
  std::string name;
  Channels channels;
  bool tiled = false;
};
void write_multi_part(const fs::path& file, const GBuffer& g, const std::vector<Part>& parts, bool strip_prefix) {
  std::vector<Imf::Header> headers;
  std::vector<Pixels> pixels(parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    Imf::Header header = header_for(g, {Imf::ZIP_COMPRESSION, Imf::FLOAT, parts[i].tiled});
    header.setName(parts[i].name);
    header.setType(parts[i].tiled ? Imf::TILEDIMAGE : Imf::SCANLINEIMAGE);
    describe_channels(header, pixels[i], parts[i].channels, Imf::FLOAT, strip_prefix ? parts[i].name + "." : "");
    headers.push_back(header);
  }
  Imf::MultiPartOutputFile out(file.c_str(), headers.data(), static_cast<int>(headers.size()));
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].tiled) {
      Imf::TiledOutputPart part(out, static_cast<int>(i));
      part.setFrameBuffer(pixels[i].frame_buffer);
      part.writeTiles(0, part.numXTiles() - 1, 0, part.numYTiles() - 1);
    } else {
      Imf::OutputPart part(out, static_cast<int>(i));
      part.setFrameBuffer(pixels[i].frame_buffer);
      part.writePixels(g.height);
    }
  }
}

// Plane-by-plane comparison; tolerance relative to max(|expected|, 1).
void expect_planes_near(const Plane& actual, const Plane& expected, double tolerance, const std::string& name) {
  ASSERT_EQ(actual.size(), expected.size()) << name;
  for (std::size_t i = 0; i < expected.size(); ++i)
    ASSERT_LE(std::abs(actual[i] - expected[i]), tolerance * std::max(1.0f, std::abs(expected[i])))
        << name << " at " << i << ": read " << actual[i] << ", expected " << expected[i];
}

void expect_same_gbuffer(const GBuffer& actual, const GBuffer& expected, double tolerance = 0.0) {
  ASSERT_EQ(actual.width, expected.width);
  ASSERT_EQ(actual.height, expected.height);
  EXPECT_EQ(actual.has_per_pixel_kd(), expected.has_per_pixel_kd());
  EXPECT_EQ(actual.has_per_pixel_ks(), expected.has_per_pixel_ks());
  expect_planes_near(actual.material, expected.material, 0.0, "material");  // small integers: exact in any format
  for (int c = 0; c < 3; ++c) {
    expect_planes_near(actual.position[c], expected.position[c], tolerance, "P" + std::to_string(c));
    expect_planes_near(actual.normal[c], expected.normal[c], tolerance, "N" + std::to_string(c));
    if (expected.has_per_pixel_kd()) expect_planes_near(actual.kd[c], expected.kd[c], tolerance, "kd" + std::to_string(c));
    if (expected.has_per_pixel_ks()) expect_planes_near(actual.ks[c], expected.ks[c], tolerance, "ks" + std::to_string(c));
  }
}

TEST(Layouts, NativeLayoutIsDetectedAndDescribed) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  write_gbuffer(g, dir / "g.exr");
  const GBufferRead read = read_gbuffer(dir / "g.exr", {});
  EXPECT_EQ(read.layout, Layout::phongcl);
  EXPECT_EQ(read.description, "phongcl (P, N, material)");
  expect_same_gbuffer(read.gbuffer, g);
}

TEST(Layouts, BlenderShortPassNames) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  write_file(dir / "b.exr", g, blender_channels(scene, g, {}));
  const GBufferRead read = read_gbuffer(dir / "b.exr", colour_passes());
  EXPECT_EQ(read.layout, Layout::blender);
  EXPECT_EQ(read.description,
            "blender (view layer 'ViewLayer': Position, Normal, DiffCol, GlossCol, IndexMA, Combined.A; kd from DiffCol, "
            "ks from GlossCol)");
  EXPECT_FALSE(read.needs_positions_from_depth());
  expect_same_gbuffer(read.gbuffer, with_table_colors(scene, g));
}

// Cycles' GlossCol is the specular tint (1 on every Principled surface), not a Phong ks: the
// blender layout takes ks from the table unless asked, and says so.
TEST(Layouts, BlenderKsComesFromTheTableUnlessAsked) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  write_file(dir / "b.exr", g, blender_channels(scene, g, {}));
  const GBufferRead read = read_gbuffer(dir / "b.exr", {});
  EXPECT_EQ(read.description,
            "blender (view layer 'ViewLayer': Position, Normal, DiffCol, IndexMA, Combined.A; kd from DiffCol, ks from "
            "the scene's table; GlossCol not used as ks (--ks-from pass uses it))");
  GBuffer expected = with_table_colors(scene, g);
  expected.ks = {};
  expect_same_gbuffer(read.gbuffer, expected);
  ReadOptions table;
  table.kd = ColourSource::table;
  EXPECT_FALSE(read_gbuffer(dir / "b.exr", table).gbuffer.has_per_pixel_kd());
}

TEST(Layouts, BlenderLongPassNames) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  write_file(dir / "b.exr", g, blender_channels(scene, g, {.long_names = true}));
  const GBufferRead read = read_gbuffer(dir / "b.exr", colour_passes());
  EXPECT_EQ(read.description,
            "blender (view layer 'ViewLayer': Position, Normal, Diffuse Color, Glossy Color, Material Index, Combined.A; "
            "kd from Diffuse Color, ks from Glossy Color)");
  expect_same_gbuffer(read.gbuffer, with_table_colors(scene, g));
}

TEST(Layouts, BlenderAlphaZeroIsBackgroundEvenWithANormal) {
  TempDir dir;
  auto [scene, g] = default_scene();
  for (std::size_t i = 0; i < g.pixel_count(); ++i)
    if (!shaded(g, i)) g.normal[1][i] = 1.0f;  // some renderers leave a normal behind the alpha
  write_file(dir / "b.exr", g, blender_channels(scene, g, {.colors = false}));
  const GBufferRead read = read_gbuffer(dir / "b.exr", with_layout(Layout::blender));
  expect_same_gbuffer(read.gbuffer, g);
}

TEST(Layouts, BlenderViewLayerIsChosen) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  GBuffer other = g;
  for (float& m : other.material) m = m < 0.0f ? m : 1.0f;  // a layer that differs
  Channels channels = blender_channels(scene, g, {.layer = "Foreground", .colors = false});
  for (auto& channel : blender_channels(scene, other, {.layer = "Background", .colors = false}))
    channels.push_back(std::move(channel));
  write_file(dir / "b.exr", g, channels);

  try {
    read_gbuffer(dir / "b.exr", {});
    FAIL() << "two layers, neither called ViewLayer: the user must choose";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("several Blender view layers (Background, Foreground): choose one with --view-layer"),
              std::string::npos) << e.what();
  }
  const GBufferRead read = read_gbuffer(dir / "b.exr", with_layout(Layout::automatic, "Background"));
  EXPECT_EQ(read.description, "blender (view layer 'Background': Position, Normal, IndexMA, Combined.A)");
  expect_same_gbuffer(read.gbuffer, other);
}

TEST(Layouts, AovStyleNamesWithoutMaterialGiveMaterialZero) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  GBuffer expected = g;
  for (float& m : expected.material) m = m < 0.0f ? -1.0f : 0.0f;
  struct Case {
    const char *position, *normal, *suffixes, *description;
  };
  for (const Case& c : {Case{"P", "N", "RGB", "aov (P, N; no material pass: material 0)"},
                        Case{"P", "N", "XYZ", "aov (P, N; no material pass: material 0)"},
                        Case{"Pworld", "Nworld", "RGB", "aov (Pworld, Nworld; no material pass: material 0)"},
                        Case{"Pworld", "Nworld", "XYZ", "aov (Pworld, Nworld; no material pass: material 0)"}}) {
    Channels channels;
    add3(channels, c.position, c.suffixes, g.position);
    add3(channels, c.normal, c.suffixes, g.normal);  // background: N = 0
    write_file(dir / "a.exr", g, channels);
    const GBufferRead read = read_gbuffer(dir / "a.exr", {});
    EXPECT_EQ(read.layout, Layout::aov) << c.description;
    EXPECT_EQ(read.description, c.description);
    expect_same_gbuffer(read.gbuffer, expected);
  }
}

TEST(Layouts, AovStyleWithMaterialAlbedoAndAlpha) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  Channels channels;
  add3(channels, "Pworld", "XYZ", g.position);
  add3(channels, "Nworld", "XYZ", g.normal);
  add3(channels, "diffuse_albedo", "RGB", table_colors(scene, g, &Material::kd));
  add3(channels, "specular_albedo", "RGB", table_colors(scene, g, &Material::ks));
  channels.push_back({"material", material_index_pass(g)});
  channels.push_back({"A", alpha_pass(g)});
  write_file(dir / "a.exr", g, channels);
  const GBufferRead read = read_gbuffer(dir / "a.exr", {});
  EXPECT_EQ(read.description, "aov (Pworld, Nworld, diffuse_albedo, specular_albedo, material, A; kd from diffuse_albedo, ks from "
            "specular_albedo)");
  expect_same_gbuffer(read.gbuffer, with_table_colors(scene, g));
}

// An aov file's beauty: the first complete source of RGBA.*, beauty.*, R G B; a partial one is no
// beauty (and no error: it is never required); the phongcl layout has none.
TEST(Layouts, AovBeautyIsTheFirstCompleteSourceAndNeverRequired) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  ReadOptions with_beauty;
  with_beauty.beauty = true;
  Planes3 red, green;
  for (int c = 0; c < 3; ++c) {
    red[c].assign(g.pixel_count(), c == 0 ? 0.75f : 0.0f);
    green[c].assign(g.pixel_count(), c == 1 ? 0.25f : 0.0f);
  }
  Channels channels;
  add3(channels, "P", "XYZ", g.position);
  add3(channels, "N", "XYZ", g.normal);
  add3(channels, "beauty", "RGB", red);
  for (int c = 0; c < 3; ++c) channels.push_back({std::string(1, "RGB"[c]), green[c]});
  channels.push_back({"RGBA.R", red[0]});  // RGBA without G and B: incomplete, skipped
  write_file(dir / "a.exr", g, channels);
  const GBufferRead read = read_gbuffer(dir / "a.exr", with_beauty);
  EXPECT_EQ(read.beauty, "beauty");
  EXPECT_EQ(read.gbuffer.beauty, red);
  EXPECT_EQ(read.description, "aov (P, N; no material pass: material 0)");

  channels.erase(std::remove_if(channels.begin(), channels.end(),
                                [](const auto& channel) { return channel.name.starts_with("beauty."); }),
                 channels.end());
  write_file(dir / "b.exr", g, channels);
  const GBufferRead rgb = read_gbuffer(dir / "b.exr", with_beauty);
  EXPECT_EQ(rgb.beauty, "RGB");
  EXPECT_EQ(rgb.gbuffer.beauty, green);

  channels.erase(std::remove_if(channels.begin(), channels.end(), [](const auto& channel) { return channel.name == "B"; }),
                 channels.end());
  write_file(dir / "c.exr", g, channels);
  const GBufferRead partial = read_gbuffer(dir / "c.exr", with_beauty);
  EXPECT_FALSE(partial.gbuffer.has_beauty());
  EXPECT_EQ(partial.beauty, "");

  write_gbuffer(g, dir / "native.exr");
  EXPECT_FALSE(read_gbuffer(dir / "native.exr", with_beauty).gbuffer.has_beauty());
}

TEST(Layouts, UserChannelMappingForAnythingElse) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  Channels channels;
  add3(channels, "world_position", "uvw", g.position);
  add3(channels, "shading_normal", "abc", g.normal);
  channels.push_back({"matid", material_index_pass(g)});
  write_file(dir / "c.exr", g, channels);
  ReadOptions options;
  for (const char* text : {"position=world_position.u,world_position.v,world_position.w",
                           "normal=shading_normal.a,shading_normal.b,shading_normal.c", "material=matid"})
    options.channels.insert(parse_channel_assignment(text));
  const GBufferRead read = read_gbuffer(dir / "c.exr", options);
  EXPECT_EQ(read.layout, Layout::custom);
  EXPECT_NE(read.description.find("position=world_position.u,world_position.v,world_position.w"), std::string::npos)
      << read.description;
  expect_same_gbuffer(read.gbuffer, g);  // background from the zero normal
}

TEST(Layouts, UserMappingOverridesOnePassOfAPreset) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  Channels channels = blender_channels(scene, g, {.colors = false});
  for (auto& channel : channels)
    if (channel.name == "ViewLayer.IndexMA.X") channel.name = "ViewLayer.IndexOB.X";  // object index instead
  write_file(dir / "b.exr", g, channels);
  ReadOptions options;
  options.channels.insert(parse_channel_assignment("material=ViewLayer.IndexOB.X"));
  const GBufferRead read = read_gbuffer(dir / "b.exr", options);
  EXPECT_EQ(read.description, "blender (view layer 'ViewLayer': Position, Normal, material=ViewLayer.IndexOB.X, Combined.A)");
  expect_same_gbuffer(read.gbuffer, g);
}

TEST(Layouts, MultiPartFiles) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  const Channels all = blender_channels(scene, g, {});
  // Nuke style: one part per layer, named after it, channels without the layer prefix; and a
  // file split by pass into tiled and scanline parts with full channel names.
  write_multi_part(dir / "nuke.exr", g, {{"ViewLayer", all}}, true);
  std::vector<Part> split{{"geometry", {}, true}, {"material", {}, false}};
  for (const auto& channel : all)
    split[channel.name.find("Position") != std::string::npos || channel.name.find("Normal") != std::string::npos ? 0 : 1]
        .channels.push_back(channel);
  write_multi_part(dir / "split.exr", g, split, false);
  for (const char* name : {"nuke.exr", "split.exr"}) {
    const GBufferRead read = read_gbuffer(dir / name, colour_passes());
    EXPECT_EQ(read.layout, Layout::blender) << name;
    expect_same_gbuffer(read.gbuffer, with_table_colors(scene, g));
  }
}

// Reads one channel with OpenEXR's own API: what any EXR reader decodes from the file.
Plane decode_with_openexr(const fs::path& file, const std::string& name) {
  Imf::InputFile in(file.c_str());
  const Imath::Box2i window = in.header().dataWindow();
  Plane plane(static_cast<std::size_t>(window.max.x - window.min.x + 1) * (window.max.y - window.min.y + 1));
  Imf::FrameBuffer frame_buffer;
  frame_buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, plane.data(), window));
  in.setFrameBuffer(frame_buffer);
  in.readPixels(window.min.y, window.max.y);
  return plane;
}

TEST(Layouts, EveryCompressionHalfAndFloatTiledAndScanline) {
  TempDir dir;
  // An offset data window inside a larger display window, too: renderers crop to the region rendered.
  auto [scene, g] = default_scene();
  g.data_window = {3, -2, 3 + g.width - 1, -2 + g.height - 1};
  g.display_window = {0, 0, 127, 63};
  const Channels channels = blender_channels(scene, g, {});
  const GBuffer expected = with_table_colors(scene, g);
  // Tolerances against what was written, relative to max(|value|, 1): lossless codecs give the
  // values back exactly in float and rounded to half's 11-bit significand (2^-11) in half. PXR24
  // keeps 15 of float's 23 significand bits (rounded: 2^-16; 2^-15 allows for the rounding of the
  // rounding). B44 and DWA are lossy by design (DWA only on R/G/B-named channels, so the colour
  // passes): there the loose bound only catches a wrong channel or pixel, and the exact check is
  // against OpenEXR's own decoding of the same file.
  struct Case {
    Imf::Compression compression;
    Imf::PixelType type;
    double tolerance;
  };
  const double half_rounding = std::ldexp(1.0, -11);
  const std::vector<Case> cases = {
      {Imf::NO_COMPRESSION, Imf::FLOAT, 0.0},      {Imf::NO_COMPRESSION, Imf::HALF, half_rounding},
      {Imf::RLE_COMPRESSION, Imf::FLOAT, 0.0},     {Imf::RLE_COMPRESSION, Imf::HALF, half_rounding},
      {Imf::ZIPS_COMPRESSION, Imf::FLOAT, 0.0},    {Imf::ZIPS_COMPRESSION, Imf::HALF, half_rounding},
      {Imf::ZIP_COMPRESSION, Imf::FLOAT, 0.0},     {Imf::ZIP_COMPRESSION, Imf::HALF, half_rounding},
      {Imf::PIZ_COMPRESSION, Imf::FLOAT, 0.0},     {Imf::PIZ_COMPRESSION, Imf::HALF, half_rounding},
      {Imf::PXR24_COMPRESSION, Imf::FLOAT, std::ldexp(1.0, -15)},
      {Imf::PXR24_COMPRESSION, Imf::HALF, half_rounding},
      {Imf::B44_COMPRESSION, Imf::HALF, 0.1},      {Imf::B44A_COMPRESSION, Imf::HALF, 0.1},
      {Imf::DWAA_COMPRESSION, Imf::HALF, 0.1},     {Imf::DWAA_COMPRESSION, Imf::FLOAT, 0.1},
      {Imf::DWAB_COMPRESSION, Imf::HALF, 0.1},     {Imf::DWAB_COMPRESSION, Imf::FLOAT, 0.1},
  };
  for (const Case& c : cases) {
    for (bool tiled : {false, true}) {
      const std::string what = compression_name(c.compression) + (c.type == Imf::HALF ? " half" : " float") + (tiled ? " tiled" : " scanline");
      SCOPED_TRACE(what);
      const fs::path file = dir / "b.exr";
      write_file(file, g, channels, {c.compression, c.type, tiled});
      const GBufferRead read = read_gbuffer(file, colour_passes());
      EXPECT_EQ(read.gbuffer.data_window.x_min, 3);
      EXPECT_EQ(read.gbuffer.data_window.y_min, -2);
      EXPECT_EQ(read.gbuffer.display_window.x_max, 127);
      // Exactly what OpenEXR decodes: our plumbing adds nothing to the codec's loss. The lossy
      // codecs (B44, DWA) shorten normals, which the edge policy reads as partial coverage or as
      // two surfaces meeting and so changes the colour passes there: for them positions only.
      if (c.tolerance <= half_rounding)
        expect_planes_near(read.gbuffer.kd[0], decode_with_openexr(file, "ViewLayer.DiffCol.R"), 0.0, "DiffCol.R");
      expect_planes_near(read.gbuffer.position[2], decode_with_openexr(file, "ViewLayer.Position.Z"), 0.0, "Position.Z");
      if (c.compression == Imf::B44_COMPRESSION || c.compression == Imf::B44A_COMPRESSION) continue;  // see below
      expect_same_gbuffer(read.gbuffer, expected, c.tolerance);
    }
  }
}

// B44 quantises each 4x4 block of half values relative to the block's range: a codec for images,
// not geometry. Colour passes stay within 0.1 (0.05 seen), but index passes do not survive (a 3
// next to a 0 came back as 4), so this checks colours only; the exact check against OpenEXR's own
// decoding is in the test above. docs/formats.md: do not write G-buffers with B44.
TEST(Layouts, B44KeepsColoursClose) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  const GBuffer expected = with_table_colors(scene, g);
  for (Imf::Compression compression : {Imf::B44_COMPRESSION, Imf::B44A_COMPRESSION}) {
    SCOPED_TRACE(compression_name(compression));
    write_file(dir / "b.exr", g, blender_channels(scene, g, {}), {compression, Imf::HALF, false});
    const GBufferRead read = read_gbuffer(dir / "b.exr", {});
    for (int c = 0; c < 3; ++c) expect_planes_near(read.gbuffer.kd[c], expected.kd[c], 0.1, "kd");
  }
}

// Reconstructed positions against the position pass they replace. Float rounding, per coordinate:
// the stored depth carries 2^-24 relative error (so t * 2^-24 along the ray), the written and the
// rebuilt positions 2^-24 * |P| each; the ray itself is double. Allowing twice the sum:
// |error| <= 2^-23 * (depth + 2 * max|P|). A wrong convention or pixel-centre offset errs by far
// more (1/cos of the off-axis angle, or a pixel's footprint at that distance).
void expect_positions_from_depth(const GBuffer& rebuilt, const GBuffer& truth, const Plane& depth) {
  for (std::size_t i = 0; i < truth.pixel_count(); ++i) {
    if (!shaded(truth, i)) continue;
    const float largest = std::max({std::abs(truth.position[0][i]), std::abs(truth.position[1][i]), std::abs(truth.position[2][i])});
    const double tolerance = std::ldexp(1.0, -23) * (std::abs(depth[i]) + 2.0 * largest);
    for (int c = 0; c < 3; ++c)
      ASSERT_LE(std::abs(rebuilt.position[c][i] - truth.position[c][i]), tolerance)
          << "pixel " << i << " axis " << c << ": rebuilt " << rebuilt.position[c][i] << ", true " << truth.position[c][i];
  }
}

TEST(DepthReconstruction, BothConventionsMatchThePositionPass) {
  TempDir dir;
  auto [scene, g] = default_scene();
  // A crop of the camera's image: data window pixel (x, y) must still get the camera's ray (x, y).
  GBuffer crop = g;
  const PixelWindow window{20, 10, 80, 50};
  crop.data_window = window;
  crop.width = window.width();
  crop.height = window.height();
  const int width = g.width;  // clang 14 cannot capture a structured binding
  const auto crop_plane = [&](const Plane& plane) {
    Plane out;
    for (int y = window.y_min; y <= window.y_max; ++y)
      for (int x = window.x_min; x <= window.x_max; ++x) out.push_back(plane[static_cast<std::size_t>(y) * width + x]);
    return out;
  };
  for (int c = 0; c < 3; ++c) crop.position[c] = crop_plane(g.position[c]), crop.normal[c] = crop_plane(g.normal[c]);
  crop.material = crop_plane(g.material);

  for (const GBuffer* truth : {&g, &crop}) {
    for (auto [kind, convention] : {std::pair{DepthPass::distance, DepthConvention::distance},
                                    std::pair{DepthPass::view_z, DepthConvention::view_z}}) {
      SCOPED_TRACE(std::string(kind == DepthPass::distance ? "distance" : "view z") + (truth == &crop ? ", cropped" : ""));
      write_file(dir / "d.exr", *truth, blender_channels(scene, *truth, {.position = false, .depth = kind, .colors = false}));
      GBufferRead read = read_gbuffer(dir / "d.exr", {});
      ASSERT_TRUE(read.needs_positions_from_depth());
      EXPECT_NE(read.description.find("Depth"), std::string::npos) << read.description;
      positions_from_depth(read.gbuffer, read.depth, scene.camera, convention);
      expect_positions_from_depth(read.gbuffer, *truth, read.depth);
      expect_same_gbuffer(read.gbuffer, *truth, 1e-5);  // normals and materials untouched
    }
  }
}

TEST(DepthReconstruction, TheConventionsDifferOffAxis) {
  // Guards the test above against passing for either convention: the wrong one must fail it.
  auto [scene, g] = default_scene();
  GBuffer rebuilt = g;
  positions_from_depth(rebuilt, depth_pass(scene, g, DepthPass::distance), scene.camera, DepthConvention::view_z);
  double worst = 0.0;
  for (std::size_t i = 0; i < g.pixel_count(); ++i)
    if (shaded(g, i)) worst = std::max(worst, static_cast<double>(std::abs(rebuilt.position[0][i] - g.position[0][i])));
  EXPECT_GT(worst, 1e-2);
}

TEST(DepthReconstruction, DisplayWindowMustBeTheCameraImage) {
  auto [scene, g] = default_scene();
  g.source = "small.exr";
  scene.camera.width += 1;
  try {
    positions_from_depth(g, Plane(g.pixel_count(), 1.0f), scene.camera, DepthConvention::distance);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("small.exr: display window is 97x61 but the scene camera is 98x61"),
              std::string::npos) << e.what();
  }
}

TEST(CameraSpace, TheCameraGoesToTheOriginLookingDownMinusZ) {
  const Scene scene = load_scene(kDefaultScene);
  const glm::dmat4 view = world_to_camera(scene.camera);
  const glm::dvec3 eye(view * glm::dvec4(scene.camera.eye, 1.0));
  const glm::dvec3 target(view * glm::dvec4(scene.camera.look_at, 1.0));
  EXPECT_NEAR(glm::length(eye), 0.0, 1e-12);
  EXPECT_NEAR(target.x, 0.0, 1e-12);
  EXPECT_NEAR(target.y, 0.0, 1e-12);
  EXPECT_NEAR(target.z, -glm::length(scene.camera.look_at - scene.camera.eye), 1e-12);
  const Scene moved = to_camera_space(scene);
  EXPECT_EQ(moved.camera.eye, glm::dvec3(0.0));
  EXPECT_EQ(moved.camera.look_at, glm::dvec3(0.0, 0.0, -1.0));
  ASSERT_EQ(moved.lights.size(), scene.lights.size());
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {  // rigid: distances to the eye are kept
    if (scene.lights[i].type == LightType::point)
      EXPECT_NEAR(glm::length(moved.lights[i].position), glm::length(scene.lights[i].position - scene.camera.eye), 1e-12);
    else
      EXPECT_NEAR(glm::length(moved.lights[i].direction), glm::length(scene.lights[i].direction), 1e-12);
  }
}

// The same G-buffer moved into camera space with world_to_camera (positions and normals).
GBuffer in_camera_space(const GBuffer& g, const Camera& camera) {
  const glm::dmat4 view = world_to_camera(camera);
  GBuffer moved = g;
  for (std::size_t i = 0; i < g.pixel_count(); ++i) {
    const glm::dvec3 p(view * glm::dvec4(g.position[0][i], g.position[1][i], g.position[2][i], 1.0));
    const glm::dvec3 n(view * glm::dvec4(g.normal[0][i], g.normal[1][i], g.normal[2][i], 0.0));
    for (int c = 0; c < 3; ++c) moved.position[c][i] = static_cast<float>(p[c]), moved.normal[c][i] = static_cast<float>(n[c]);
  }
  return moved;
}

TEST(CameraSpace, ShadesLikeWorldSpace) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const auto [scene, g] = default_scene();
  const Image world = shader.shade(scene, g, {}).image;
  for (const auto& [what, camera_gbuffer] :
       {std::pair{"moved by world_to_camera", in_camera_space(g, scene.camera)},
        std::pair{"generated from the camera-space scene", generate_gbuffer(to_camera_space(scene))}}) {
    SCOPED_TRACE(what);
    const Image camera = shader.shade(to_camera_space(scene), camera_gbuffer, {}).image;
    // Same bound as the kernel-vs-reference suites: the inputs differ only by float rounding of a
    // rigid motion (a few ulps of P and N), far below it.
    const ErrorStats stats = compare_images(camera, world, 1e-6, testing::shaded_mask(g));
    EXPECT_LE(stats.max_rel, 5e-4) << testing::describe_worst(stats);
    EXPECT_EQ(stats.nonfinite_mismatches, 0u);
  }
}

TEST(AovOutput, LayersSumToTheCombinedImage) {
  PHONGCL_REQUIRE_DEVICE(shader);
  TempDir dir;
  const auto [scene, g] = default_scene();
  ShadeOptions options;
  options.write_terms = true;
  const ShadeResult result = shader.shade(scene, g, options);
  for (ExrPixelType type : {ExrPixelType::float32, ExrPixelType::half}) {
    const fs::path file = dir / "aov.exr";
    write_layered_exr({{"", &result.image, true},
                       {"ambient", &result.terms.ambient, false},
                       {"diffuse", &result.terms.diffuse, false},
                       {"specular", &result.terms.specular, false}},
                      file, type);
    // Read back with OpenEXR's API, not ours.
    const Imf::InputFile in(file.c_str());
    std::vector<std::string> names;
    for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) names.emplace_back(it.name());
    EXPECT_EQ(names, (std::vector<std::string>{"A", "B", "G", "R", "ambient.B", "ambient.G", "ambient.R", "diffuse.B",
                                               "diffuse.G", "diffuse.R", "specular.B", "specular.G", "specular.R"}));
    EXPECT_EQ(in.header().channels().findChannel("diffuse.G")->type, type == ExrPixelType::half ? Imf::HALF : Imf::FLOAT);
    const auto alpha = decode_with_openexr(file, "A");
    for (const char* c : {"R", "G", "B"}) {
      const auto combined = decode_with_openexr(file, c), ambient = decode_with_openexr(file, std::string("ambient.") + c),
                 diffuse = decode_with_openexr(file, std::string("diffuse.") + c),
                 specular = decode_with_openexr(file, std::string("specular.") + c);
      for (std::size_t i = 0; i < combined.size(); ++i) {
        if (alpha[i] == 0.0f) continue;  // background: the scene's colour, not a sum of terms
        // The kernel adds the three terms in float (a few ulps); half storage rounds each of the
        // four values by up to 2^-11 relative: bound by 4 * 2^-11 of the largest.
        const double sum = static_cast<double>(ambient[i]) + diffuse[i] + specular[i];
        const double scale = std::max({1e-6, std::abs(sum), static_cast<double>(std::abs(combined[i]))});
        const double tolerance = (type == ExrPixelType::half ? 4.0 * std::ldexp(1.0, -11) : 1e-5) * scale;
        ASSERT_NEAR(sum, combined[i], tolerance) << c << " at pixel " << i;
      }
    }
  }
}

// Runs the phongcl binary; returns the exit status, stdout and stderr.
struct CliRun {
  int status;
  std::string out, err;
};
std::string slurp(const fs::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
CliRun run_phongcl(const std::string& arguments, const TempDir& dir) {
  const std::string command = std::string("\"") + PHONGCL_EXE + "\" " + arguments + " > \"" + (dir / "stdout").string() +
                              "\" 2> \"" + (dir / "stderr").string() + "\"";
  const int raw = std::system(command.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(dir / "stdout"), slurp(dir / "stderr")};
}
std::string quoted(const fs::path& path) { return "\"" + path.string() + "\""; }

TEST(LayoutsCli, RendererFilesShadeWithOnlySceneAndGBuffer) {
  PHONGCL_REQUIRE_DEVICE(shader);
  (void)shader;  // the binary opens the same default device itself
  TempDir dir;
  Scene scene = load_scene(kDefaultScene);  // the scene file's own camera and size
  const GBuffer g = generate_gbuffer(scene);
  write_gbuffer(g, dir / "native.exr");
  write_file(dir / "short.exr", g, blender_channels(scene, g, {}));
  write_file(dir / "long.exr", g, blender_channels(scene, g, {.long_names = true}));
  write_file(dir / "depth.exr", g, blender_channels(scene, g, {.position = false, .depth = DepthPass::view_z}));
  Channels aov;
  add3(aov, "P", "RGB", g.position);
  add3(aov, "N", "RGB", g.normal);
  aov.push_back({"material", material_index_pass(g)});
  write_file(dir / "aov.exr", g, aov);

  const std::string scene_arg = "--scene " + quoted(kDefaultScene);
  const CliRun native = run_phongcl("shade " + scene_arg + " --gbuffer " + quoted(dir / "native.exr") + " --out " +
                                     quoted(dir / "native_lit.exr"), dir);
  ASSERT_EQ(native.status, 0) << native.err;
  EXPECT_NE(native.out.find("  layout     phongcl (P, N, material)\n"), std::string::npos) << native.out;
  const Image expected = read_exr(dir / "native_lit.exr");

  write_gbuffer(in_camera_space(g, scene.camera), dir / "camera.exr");

  struct Case {
    const char *file, *flags, *announced;
  };
  for (const Case& c : {Case{"short.exr", "--ks-from pass", "layout     blender (view layer 'ViewLayer': Position, Normal, DiffCol, GlossCol, IndexMA"},
                        Case{"long.exr", "--ks-from pass", "layout     blender (view layer 'ViewLayer': Position, Normal, Diffuse Color, Glossy Color, Material Index"},
                        Case{"depth.exr", "", "positions from depth; kd from DiffCol, ks from the scene's table; GlossCol not used as ks (--ks-from pass uses it)), depth = view-space z (Blender's Depth pass is view-space z; --depth-convention overrides)"},
                        Case{"aov.exr", "", "layout     aov (P, N, material)"},
                        Case{"camera.exr", "--space camera", "space      camera"}}) {
    SCOPED_TRACE(c.file);
    const CliRun run = run_phongcl("shade " + scene_arg + " --gbuffer " + quoted(dir / c.file) + " --out " +
                                    quoted(dir / "lit.exr") + " --aov " + quoted(dir / "aov_out.exr") + " " + c.flags, dir);
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find(c.announced), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("aov_out.exr (ambient, diffuse, specular + combined, float32)"), std::string::npos) << run.out;
    const ErrorStats stats = compare_images(read_exr(dir / "lit.exr"), expected, 1e-6, testing::shaded_mask(g));
    // Per-pixel colours instead of the table, positions rebuilt from depth or moved into camera
    // space (a few ulps of P and N): well inside the kernel's own bound.
    EXPECT_LE(stats.max_rel, 5e-4) << testing::describe_worst(stats);
    const ErrorStats combined = compare_images(read_exr(dir / "aov_out.exr"), read_exr(dir / "lit.exr"), 1e-6);
    EXPECT_EQ(combined.max_abs, 0.0) << "the AOV file's R G B A is the combined image";
  }
}

TEST(LayoutsCli, BadLayoutOrChannelIsOneLineAndKeepsTheOutput) {
  TempDir dir;
  const Scene scene = load_scene(kDefaultScene);
  const auto [small_scene, g] = default_scene();
  write_file(dir / "b.exr", g, blender_channels(small_scene, g, {}));
  std::ofstream(dir / "lit.exr") << "previous result";
  const std::string common = "shade --scene " + quoted(kDefaultScene) + " --gbuffer " + quoted(dir / "b.exr") +
                             " --out " + quoted(dir / "lit.exr");
  struct Case {
    std::string flags;
    std::vector<std::string> expected;
  };
  for (const Case& c : {Case{"--layout maya", {"unknown --layout 'maya' (choose auto, phongcl, blender or aov)"}},
                        Case{"--channel position=Foo.X,Foo.Y,Foo.Z",
                             {(dir / "b.exr").string(), "--channel position: no channel 'Foo.X'", "found: ", "ViewLayer.Normal.X"}},
                        Case{"--channel colour=A", {"unknown pass 'colour'"}},
                        Case{"--layout aov", {(dir / "b.exr").string(), "missing channels P.X, P.Y, P.Z"}},
                        Case{"--view-layer Missing", {"missing channels Missing.Position.X"}}}) {
    SCOPED_TRACE(c.flags);
    const CliRun run = run_phongcl(common + " " + c.flags, dir);
    EXPECT_NE(run.status, 0);
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    for (const auto& part : c.expected) EXPECT_NE(run.err.find(part), std::string::npos) << run.err;
    EXPECT_EQ(slurp(dir / "lit.exr"), "previous result");
  }
}

TEST(LayoutErrors, MissingBlenderPassNamesChannelsAndWhatWasFound) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  Channels channels = blender_channels(scene, g, {.colors = false});
  std::erase_if(channels, [](const Channel& c) { return c.name == "ViewLayer.Normal.Y"; });
  write_file(dir / "b.exr", g, channels);
  try {
    read_gbuffer(dir / "b.exr", {});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((dir / "b.exr").string() + ": missing channel ViewLayer.Normal.Y (blender layout; found: "),
              std::string::npos) << message;
    EXPECT_NE(message.find("ViewLayer.Normal.Z"), std::string::npos) << message;
  }
}

TEST(LayoutErrors, IncompleteColourPass) {
  TempDir dir;
  const auto [scene, g] = default_scene();
  Channels channels = blender_channels(scene, g, {});
  std::erase_if(channels, [](const Channel& c) { return c.name == "ViewLayer.GlossCol.B"; });
  write_file(dir / "b.exr", g, channels);
  try {
    read_gbuffer(dir / "b.exr", colour_passes());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("incomplete per-pixel material group, missing ViewLayer.GlossCol.B"),
              std::string::npos) << e.what();
  }
}

TEST(LayoutErrors, FlagValues) {
  EXPECT_EQ(parse_layout("blender"), Layout::blender);
  EXPECT_EQ(parse_layout("auto"), Layout::automatic);
  EXPECT_THROW(parse_layout("custom"), InputError);  // what auto reports, not a choice
  const auto [pass, channels] = parse_channel_assignment("kd=ViewLayer.Diffuse Color.R,ViewLayer.Diffuse Color.G,ViewLayer.Diffuse Color.B");
  EXPECT_EQ(pass, Pass::kd);
  EXPECT_EQ(channels[1], "ViewLayer.Diffuse Color.G");
  for (const char* bad : {"position", "position=A,B", "material=A,B", "position=A,,C", "colour=R"}) {
    try {
      parse_channel_assignment(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--channel ") + bad), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace phongcl
