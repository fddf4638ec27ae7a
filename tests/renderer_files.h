#pragma once
// G-buffer files as renderers write them, made here with OpenEXR's own API (not phongcl's writer):
// Blender's and AOV-style channel names, every compression, multi-part files; and files read back
// the same way, so that a test compares phongcl's reader with what any EXR reader decodes.
#include <gtest/gtest.h>

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
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gbuffer/layouts.h"
#include "raycast/raycast.h"
#include "scene/camera_space.h"
#include "scene/scene.h"

namespace phongcl::testing {

namespace fs = std::filesystem;

inline const fs::path kSourceDir = PHONGCL_SOURCE_DIR;
inline const fs::path kDefaultScene = kSourceDir / "scenes/default/scene.json";

// The default scene at a small size (odd, so no block or tile size divides it) and its G-buffer.
struct Fixture {
  Scene scene;
  GBuffer native;
};
inline Fixture default_scene(int width = 97, int height = 61) {
  Scene scene = load_scene(kDefaultScene);
  scene.camera.width = width;
  scene.camera.height = height;
  return {scene, generate_gbuffer(scene)};
}

inline bool shaded(const GBuffer& g, std::size_t i) { return g.material[i] >= 0.0f; }

// A per-pixel colour plane from the material table (0 on background), as a renderer's colour pass.
inline Planes3 table_colors(const Scene& scene, const GBuffer& g, glm::dvec3 Material::*color) {
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

inline void add3(Channels& channels, const std::string& base, const char* suffixes, const Planes3& planes) {
  for (int c = 0; c < 3; ++c) channels.push_back({base + "." + suffixes[c], planes[c]});
}

inline Plane material_index_pass(const GBuffer& g) {  // renderers write 0, not -1, where nothing was hit
  Plane index = g.material;
  for (float& value : index) value = std::max(value, 0.0f);
  return index;
}

inline Plane alpha_pass(const GBuffer& g) {
  Plane alpha(g.pixel_count());
  for (std::size_t i = 0; i < alpha.size(); ++i) alpha[i] = shaded(g, i) ? 1.0f : 0.0f;
  return alpha;
}

enum class DepthPass { none, distance, view_z };

inline Plane depth_pass(const Scene& scene, const GBuffer& g, DepthPass kind) {
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
inline Channels blender_channels(const Scene& scene, const GBuffer& g, const BlenderStyle& style) {
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
inline ReadOptions colour_passes() {
  ReadOptions options;
  options.kd = options.ks = ColourSource::pass;
  return options;
}

inline ReadOptions with_layout(Layout layout, const std::string& view_layer = "") {
  ReadOptions options;
  options.layout = layout;
  options.view_layer = view_layer;
  return options;
}

// What reading a Blender file must give: the native buffer plus per-pixel kd and ks.
inline GBuffer with_table_colors(const Scene& scene, GBuffer g) {
  g.kd = table_colors(scene, g, &Material::kd);
  g.ks = table_colors(scene, g, &Material::ks);
  return g;
}

struct FileFormat {
  Imf::Compression compression = Imf::ZIP_COMPRESSION;
  Imf::PixelType type = Imf::FLOAT;
  bool tiled = false;
};

inline std::string compression_name(Imf::Compression compression) {
  static const char* const kNames[] = {"NO", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB"};
  return kNames[compression];
}

inline Imf::Header header_for(const GBuffer& g, const FileFormat& format) {
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
inline void describe_channels(Imf::Header& header, Pixels& pixels, const Channels& channels, Imf::PixelType type, const std::string& strip_prefix = "") {
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

inline void write_file(const fs::path& file, const GBuffer& g, const Channels& channels, const FileFormat& format = {}) {
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
inline void write_multi_part(const fs::path& file, const GBuffer& g, const std::vector<Part>& parts, bool strip_prefix) {
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
inline void expect_planes_near(const Plane& actual, const Plane& expected, double tolerance, const std::string& name) {
  ASSERT_EQ(actual.size(), expected.size()) << name;
  for (std::size_t i = 0; i < expected.size(); ++i)
    ASSERT_LE(std::abs(actual[i] - expected[i]), tolerance * std::max(1.0f, std::abs(expected[i])))
        << name << " at " << i << ": read " << actual[i] << ", expected " << expected[i];
}

inline void expect_same_gbuffer(const GBuffer& actual, const GBuffer& expected, double tolerance = 0.0) {
  ASSERT_EQ(actual.width, expected.width);
  ASSERT_EQ(actual.height, expected.height);
  EXPECT_EQ(actual.has_per_pixel_kd(), expected.has_per_pixel_kd());
  EXPECT_EQ(actual.has_per_pixel_ks(), expected.has_per_pixel_ks());
  expect_planes_near(actual.material, expected.material, 0.0, "material");  // small integers: exact in any format
  for (int c = 0; c < 3; ++c) {
    const std::string axis = std::to_string(c);
    expect_planes_near(actual.position[c], expected.position[c], tolerance, "P" + axis);
    expect_planes_near(actual.normal[c], expected.normal[c], tolerance, "N" + axis);
    if (expected.has_per_pixel_kd()) expect_planes_near(actual.kd[c], expected.kd[c], tolerance, "kd" + axis);
    if (expected.has_per_pixel_ks()) expect_planes_near(actual.ks[c], expected.ks[c], tolerance, "ks" + axis);
  }
}

// A file's channels as OpenEXR decodes them (float), by name, without phongcl's reader.
struct Passes {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> channels;

  float at(const std::string& name, int x, int y) const { return channels.at(name)[std::size_t(y) * width + x]; }
  glm::dvec3 vec(const std::string& base, int x, int y, const char* suffixes = "XYZ") const {
    return {at(base + "." + suffixes[0], x, y), at(base + "." + suffixes[1], x, y), at(base + "." + suffixes[2], x, y)};
  }
};

inline Passes read_passes(const fs::path& file, const std::vector<std::string>& names) {
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

// One channel as OpenEXR decodes it: what any EXR reader gets from the file.
inline Plane decode_with_openexr(const fs::path& file, const std::string& name) {
  return read_passes(file, {name}).channels.at(name);
}

// The same G-buffer moved into camera space with world_to_camera (positions and normals).
inline GBuffer in_camera_space(const GBuffer& g, const Camera& camera) {
  const glm::dmat4 view = world_to_camera(camera);
  GBuffer moved = g;
  for (std::size_t i = 0; i < g.pixel_count(); ++i) {
    const glm::dvec3 p(view * glm::dvec4(g.position[0][i], g.position[1][i], g.position[2][i], 1.0));
    const glm::dvec3 n(view * glm::dvec4(g.normal[0][i], g.normal[1][i], g.normal[2][i], 0.0));
    for (int c = 0; c < 3; ++c) moved.position[c][i] = static_cast<float>(p[c]), moved.normal[c][i] = static_cast<float>(n[c]);
  }
  return moved;
}

}  // namespace phongcl::testing
