// G-buffer files: layouts OpenEXR can produce (scanline, tiled, half/float/uint, offset windows),
// the errors a user can meet, and which pixels get shaded.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfTiledOutputFile.h>
#include <half.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "common/error.h"
#include "gbuffer/gbuffer.h"
#include "gbuffer/layouts.h"
#include "gbuffer/material_check.h"

#include "temp_dir.h"

namespace phongcl {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Distinct, non-representable-in-half values per channel and pixel, so a swapped channel, a
// transposed row or a lost conversion shows up.
float sample(int channel, int x, int y) { return 0.1f * static_cast<float>(channel + 1) + x + 100.0f * y + 1.0f / 3.0f; }

GBuffer make_gbuffer(PixelWindow window, bool per_pixel_kd_and_shininess) {
  GBuffer g;
  g.data_window = window;
  g.display_window = window;
  g.width = window.width();
  g.height = window.height();
  const auto fill = [&](Plane& plane, int channel) {
    plane.resize(g.pixel_count());
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x) plane[y * g.width + x] = sample(channel, x + window.x_min, y + window.y_min);
  };
  for (int c = 0; c < 3; ++c) fill(g.position[c], c), fill(g.normal[c], 3 + c);
  g.material.assign(g.pixel_count(), 0.0f);
  for (std::size_t i = 0; i < g.pixel_count(); ++i) g.material[i] = static_cast<float>(i % 3) - 1.0f;  // -1, 0, 1
  if (per_pixel_kd_and_shininess) {
    for (int c = 0; c < 3; ++c) fill(g.kd[c], 6 + c);
    fill(g.shininess, 9);
  }
  return g;
}

void expect_planes_equal(const Plane& actual, const Plane& expected, const char* name) {
  ASSERT_EQ(actual.size(), expected.size()) << name;
  // Float32 storage is lossless: any difference is a bug in the plumbing, not rounding.
  for (std::size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(actual[i], expected[i]) << name << " at " << i;
}

void expect_same_gbuffer(const GBuffer& actual, const GBuffer& expected) {
  EXPECT_EQ(actual.width, expected.width);
  EXPECT_EQ(actual.height, expected.height);
  for (int c = 0; c < 3; ++c) {
    expect_planes_equal(actual.position[c], expected.position[c], "P");
    expect_planes_equal(actual.normal[c], expected.normal[c], "N");
    expect_planes_equal(actual.kd[c], expected.kd[c], "Kd");
  }
  expect_planes_equal(actual.material, expected.material, "material");
  expect_planes_equal(actual.shininess, expected.shininess, "shininess");
}

// Every channel of `g` that is in use, by EXR name, for writing files by hand.
std::map<std::string, const Plane*> channels_of(const GBuffer& g) {
  std::map<std::string, const Plane*> channels{
      {"P.X", &g.position[0]}, {"P.Y", &g.position[1]}, {"P.Z", &g.position[2]},
      {"N.X", &g.normal[0]},   {"N.Y", &g.normal[1]},   {"N.Z", &g.normal[2]},
      {"material", &g.material}};
  if (g.has_per_pixel_kd()) channels.insert({{"Kd.R", &g.kd[0]}, {"Kd.G", &g.kd[1]}, {"Kd.B", &g.kd[2]}});
  if (g.has_per_pixel_shininess()) channels.insert({"shininess", &g.shininess});
  return channels;
}

// Writes channels with OpenEXR's own API (not ours), each in the given file pixel type
// (default FLOAT), scanline or tiled. UINT channels hold the values converted to uint32.
void write_by_hand(const fs::path& file, const GBuffer& g, const std::map<std::string, const Plane*>& channels,
                   bool tiled, const std::map<std::string, Imf::PixelType>& types = {}) {
  const Imath::Box2i data{{g.data_window.x_min, g.data_window.y_min}, {g.data_window.x_max, g.data_window.y_max}};
  const Imath::Box2i display{{g.display_window.x_min, g.display_window.y_min},
                             {g.display_window.x_max, g.display_window.y_max}};
  Imf::Header header(display, data);
  Imf::FrameBuffer frame_buffer;
  // OpenEXR converts types on reading only: UINT and HALF channels need memory of their own type.
  std::vector<std::vector<std::uint32_t>> uint_planes;
  std::vector<std::vector<half>> half_planes;
  uint_planes.reserve(channels.size());
  half_planes.reserve(channels.size());
  for (const auto& [name, plane] : channels) {
    const auto type = types.count(name) ? types.at(name) : Imf::FLOAT;
    header.channels().insert(name, Imf::Channel(type));
    if (type == Imf::UINT) {
      auto& values = uint_planes.emplace_back();
      for (float v : *plane) values.push_back(static_cast<std::uint32_t>(v));
      frame_buffer.insert(name, Imf::Slice::Make(Imf::UINT, values.data(), data));
    } else if (type == Imf::HALF) {
      auto& values = half_planes.emplace_back(plane->begin(), plane->end());
      frame_buffer.insert(name, Imf::Slice::Make(Imf::HALF, values.data(), data));
    } else {
      frame_buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, plane->data(), data));
    }
  }
  if (tiled) {
    header.setTileDescription(Imf::TileDescription(16, 16, Imf::ONE_LEVEL));
    Imf::TiledOutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame_buffer);
    out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
  } else {
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame_buffer);
    out.writePixels(g.height);
  }
}

// The message of the InputError that reading `file` throws ("" if it does not throw one).
std::string read_error(const fs::path& file) {
  try {
    read_gbuffer(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(GBufferFile, FloatRoundTripIsExact) {
  TempDir dir;
  const GBuffer written = make_gbuffer({0, 0, 12, 7}, true);
  write_gbuffer(written, dir / "g.exr");
  const GBuffer read = read_gbuffer(dir / "g.exr");
  expect_same_gbuffer(read, written);
  EXPECT_FALSE(read.has_per_pixel_ka());  // absent groups stay absent
  EXPECT_FALSE(read.has_per_pixel_ks());
  EXPECT_EQ(read.source, dir / "g.exr");
}

TEST(GBufferFile, HalfRoundTripWithinHalfPrecision) {
  TempDir dir;
  const GBuffer written = make_gbuffer({0, 0, 9, 4}, true);
  write_gbuffer(written, dir / "g.exr", ExrPixelType::half);
  EXPECT_EQ(Imf::InputFile((dir / "g.exr").c_str()).header().channels().findChannel("P.X")->type, Imf::HALF);

  const GBuffer read = read_gbuffer(dir / "g.exr");
  const auto expect_half_close = [](const Plane& actual, const Plane& expected, const char* name) {
    ASSERT_EQ(actual.size(), expected.size());
    // Half keeps an 11-bit significand; round-to-nearest is within half an ulp: 2^-11 relative.
    for (std::size_t i = 0; i < expected.size(); ++i)
      EXPECT_LE(std::abs(actual[i] - expected[i]), std::abs(expected[i]) * std::ldexp(1.0f, -11))
          << name << " at " << i << ": read " << actual[i] << ", wrote " << expected[i];
  };
  for (int c = 0; c < 3; ++c) {
    expect_half_close(read.position[c], written.position[c], "P");
    expect_half_close(read.normal[c], written.normal[c], "N");
    expect_half_close(read.kd[c], written.kd[c], "Kd");
  }
  expect_half_close(read.shininess, written.shininess, "shininess");
  expect_planes_equal(read.material, written.material, "material");  // small integers are exact in half
}

TEST(GBufferFile, OffsetDataWindowIsKept) {
  TempDir dir;
  GBuffer written = make_gbuffer({-3, 5, 6, 9}, false);
  written.display_window = {0, 0, 63, 31};
  write_gbuffer(written, dir / "g.exr");
  const GBuffer read = read_gbuffer(dir / "g.exr");
  EXPECT_EQ(read.width, 10);
  EXPECT_EQ(read.height, 5);
  EXPECT_EQ(read.data_window, written.data_window);
  EXPECT_EQ(read.display_window, written.display_window);
  // Plane index (y - y_min) * width + (x - x_min) holds file pixel (x, y).
  EXPECT_EQ(read.position[0][(7 - 5) * 10 + (2 - -3)], sample(0, 2, 7));
  expect_same_gbuffer(read, written);
}

TEST(GBufferFile, UnsetWindowsMeanOrigin) {
  TempDir dir;
  GBuffer written = make_gbuffer({0, 0, 3, 2}, false);
  written.data_window = written.display_window = PixelWindow{};  // built in memory, never set
  write_gbuffer(written, dir / "g.exr");
  const GBuffer read = read_gbuffer(dir / "g.exr");
  EXPECT_EQ(read.data_window.x_min, 0);
  EXPECT_EQ(read.data_window.x_max, 3);
  EXPECT_EQ(read.display_window.y_max, 2);
}

TEST(GBufferFile, ScanlineFileWithMixedPixelTypesFromOpenExr) {
  TempDir dir;
  GBuffer g = make_gbuffer({2, -4, 21, 8}, false);
  for (float& m : g.material) m = std::abs(m);  // UINT cannot hold background's -1
  write_by_hand(dir / "g.exr", g, channels_of(g), false, {{"material", Imf::UINT}, {"N.Y", Imf::FLOAT}});
  const GBuffer read = read_gbuffer(dir / "g.exr");
  EXPECT_EQ(read.data_window.y_min, -4);
  expect_same_gbuffer(read, g);
}

TEST(GBufferFile, TiledFileFromOpenExr) {
  TempDir dir;
  // 37x23 is not a multiple of the 16x16 tiles: the edge tiles are partial.
  const GBuffer g = make_gbuffer({-5, 3, 31, 25}, true);
  write_by_hand(dir / "g.exr", g, channels_of(g), true);
  const GBuffer read = read_gbuffer(dir / "g.exr");
  EXPECT_EQ(read.data_window.x_min, -5);
  EXPECT_EQ(read.data_window.y_min, 3);
  expect_same_gbuffer(read, g);
}

TEST(GBufferFile, TiledHalfFileFromOpenExr) {
  TempDir dir;
  const GBuffer g = make_gbuffer({0, 0, 17, 17}, false);
  std::map<std::string, Imf::PixelType> all_half;
  for (const auto& [name, plane] : channels_of(g)) all_half[name] = Imf::HALF;
  write_by_hand(dir / "g.exr", g, channels_of(g), true, all_half);
  const GBuffer read = read_gbuffer(dir / "g.exr");
  // Half keeps an 11-bit significand: 2^-11 relative.
  for (std::size_t i = 0; i < g.pixel_count(); ++i)
    ASSERT_NEAR(read.normal[2][i], g.normal[2][i], std::abs(g.normal[2][i]) * std::ldexp(1.0f, -11)) << i;
}

TEST(GBufferErrors, MissingChannelIsNamed) {
  TempDir dir;
  const GBuffer g = make_gbuffer({0, 0, 3, 3}, false);
  auto channels = channels_of(g);
  channels.erase("N.Y");
  write_by_hand(dir / "g.exr", g, channels, false);
  const std::string message = read_error(dir / "g.exr");
  EXPECT_NE(message.find((dir / "g.exr").string()), std::string::npos) << message;
  EXPECT_NE(message.find("missing channel N.Y (found: "), std::string::npos) << message;
  EXPECT_NE(message.find("N.X"), std::string::npos) << "the found list helps spot a misnamed channel: " << message;
}

TEST(GBufferErrors, SeveralMissingChannelsAreAllNamed) {
  TempDir dir;
  const GBuffer g = make_gbuffer({0, 0, 3, 3}, false);
  auto channels = channels_of(g);
  channels.erase("P.Z");
  channels.erase("material");
  write_by_hand(dir / "g.exr", g, channels, false);
  const std::string message = read_error(dir / "g.exr");
  EXPECT_NE(message.find("missing channels P.Z, material"), std::string::npos) << message;
}

TEST(GBufferErrors, PartialOptionalGroupNamesWhatIsMissing) {
  TempDir dir;
  const GBuffer g = make_gbuffer({0, 0, 3, 3}, false);
  auto channels = channels_of(g);
  channels["Kd.R"] = &g.material;  // any plane will do: only the channel list matters
  write_by_hand(dir / "g.exr", g, channels, false);
  const std::string message = read_error(dir / "g.exr");
  EXPECT_NE(message.find("missing Kd.G, Kd.B"), std::string::npos) << message;
}

TEST(GBufferErrors, TruncatedFileIsDetected) {
  TempDir dir;
  const GBuffer g = make_gbuffer({0, 0, 63, 63}, true);
  for (bool tiled : {false, true}) {
    for (bool to_half : {true, false}) {  // else by one byte: only the last chunk is short
      const fs::path file = dir / (tiled ? "tiled.exr" : "scanline.exr");
      if (tiled)
        write_by_hand(file, g, channels_of(g), true);
      else
        write_gbuffer(g, file);
      ASSERT_NO_THROW(read_gbuffer(file));
      fs::resize_file(file, to_half ? fs::file_size(file) / 2 : fs::file_size(file) - 1);
      const std::string message = read_error(file);
      const std::string what = std::string(tiled ? "tiled" : "scanline") + (to_half ? ", cut to half: " : ", one byte short: ");
      EXPECT_NE(message.find(file.string()), std::string::npos) << what << message;
      EXPECT_NE(message.find("truncated or corrupt"), std::string::npos) << what << message;
    }
  }
}

// Rewrites the data window in the header of a file written by OpenEXR (the attribute
// "dataWindow", type "box2i", 16 bytes: x_min, y_min, x_max, y_max), as a hostile file would.
void patch_data_window(const fs::path& file, int width, int height) {
  std::fstream stream(file, std::ios::in | std::ios::out | std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  const std::string name("dataWindow\0box2i\0", 17);
  const std::size_t at = bytes.find(name);
  ASSERT_NE(at, std::string::npos);
  const std::int32_t box[4] = {0, 0, width - 1, height - 1};
  stream.seekp(static_cast<std::streamoff>(at + name.size() + 4));
  stream.write(reinterpret_cast<const char*>(box), sizeof box);
}

// OpenEXR 3.1's C++ reader accepted a 4x4 file patched to 100000x1 and returned whatever its
// buffers held (MALLOC_PERTURB_ changed the shaded image); the one chunk decodes to 4x4 pixels.
TEST(GBufferHostile, ChunkShorterThanItsWindowIsCorrupt) {
  TempDir dir;
  for (bool tiled : {false, true}) {
    const fs::path file = dir / "g.exr";
    const GBuffer g = make_gbuffer({0, 0, 3, 3}, false);
    if (tiled)
      write_by_hand(file, g, channels_of(g), true);
    else
      write_gbuffer(g, file);
    patch_data_window(file, tiled ? 16 : 100000, tiled ? 2 : 1);  // still one tile or one chunk
    const std::string message = read_error(file);
    EXPECT_NE(message.find(file.string() + ": truncated or corrupt"), std::string::npos) << (tiled ? "tiled: " : "scanline: ") << message;
  }
}

// Turns a one-chunk scanline file into one declaring width x height whose offset table is
// complete: `chunks` entries, every one pointing at the file's only chunk.
void declare_window_with_complete_offsets(const fs::path& file, int width, int height, std::uint64_t chunks) {
  patch_data_window(file, width, height);
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  // The single offset-table entry is the one 8-byte value that points just past itself.
  std::size_t table = 0;
  for (std::uint64_t value = 0; table + 8 <= bytes.size(); ++table) {
    std::memcpy(&value, bytes.data() + table, 8);
    if (value == table + 8) break;
  }
  ASSERT_LT(table + 8, bytes.size());
  const std::uint64_t chunk = table + 8 * chunks;
  std::string offsets;
  for (std::uint64_t i = 0; i < chunks; ++i) offsets.append(reinterpret_cast<const char*>(&chunk), 8);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes.substr(0, table) << offsets << bytes.substr(table + 8);
}

// An 8.6 KB file declaring 16384x16384 with a complete offset table made phongcl allocate and zero
// 7.2 GB over 17 s before it failed; 100000x100000 ended in "phongcl: std::bad_alloc", which names
// no file.
TEST(GBufferHostile, HugeDeclaredWindowFailsBeforeAllocating) {
  TempDir dir;
  const fs::path file = dir / "g.exr";
  write_gbuffer(make_gbuffer({0, 0, 3, 3}, false), file);
  declare_window_with_complete_offsets(file, 16384, 16384, 16384 / 16);  // ZIP: 16 lines per chunk
  ASSERT_LT(fs::file_size(file), 9000u);
  std::string message = read_error(file);
  EXPECT_NE(message.find(file.string() + ": truncated or corrupt EXR: a 16384x16384 data window needs 1024 chunks"),
            std::string::npos)
      << message;
  write_gbuffer(make_gbuffer({0, 0, 3, 3}, false), file);
  declare_window_with_complete_offsets(file, 100000, 100000, 100000 / 16);
  message = read_error(file);
  EXPECT_NE(message.find(file.string() + ": declares a 100000x100000 data window (10000000000 pixels), more than the "
                                         "limit of 268435456 pixels (--max-pixels)"),
            std::string::npos)
      << message;
}

// Inputs the fuzzer found (tests/fuzz/corpus/gbuffer/regression_attribute_*): a few hundred bytes
// whose header declares an attribute of gigabytes, which OpenEXR 3.1's C++ reader allocated before
// finding the file too short (the fuzz check's 1 GB allocation limit caught it).
TEST(GBufferHostile, AttributeLargerThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
  for (const char* name : {"regression_attribute_size_past_the_file.exr", "regression_attribute_after_the_channel_list.exr",
                           "regression_fixed_size_attribute_declaring_more.exr", "regression_preview_extent_overflow.exr"}) {
    const fs::path file = fs::path(PHONGCL_SOURCE_DIR) / "tests/fuzz/corpus/gbuffer" / name;
    const std::string message = read_error(file);
    EXPECT_NE(message.find(file.string() + ": truncated or corrupt EXR header (attribute '"), std::string::npos) << message;
    EXPECT_NE(message.find(" bytes, "), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(GBufferHostile, MaxPixelsIsTheCallersLimit) {
  TempDir dir;
  const fs::path file = dir / "g.exr";
  write_gbuffer(make_gbuffer({0, 0, 3, 3}, false), file);
  ReadOptions options;
  options.max_pixels = 16;
  EXPECT_EQ(read_gbuffer(file, options).gbuffer.pixel_count(), 16u);
  options.max_pixels = 15;
  try {
    read_gbuffer(file, options);
    FAIL() << "read a 4x4 file with a limit of 15 pixels";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more than the limit of 15 pixels"), std::string::npos) << e.what();
  }
}

#if defined(__SANITIZE_ADDRESS__)
#define PHONGCL_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PHONGCL_ASAN 1
#endif
#endif

// A window within the limit that this machine (here: an address-space limit) cannot hold.
TEST(GBufferHostile, AllocationFailureNamesTheFileAndTheSize) {
#ifdef PHONGCL_ASAN
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: an RLIMIT_AS would stop it";
#else
  TempDir dir;
  const fs::path file = dir / "g.exr";
  write_gbuffer(make_gbuffer({0, 0, 3, 3}, false), file);
  patch_data_window(file, 10000000, 16);  // one ZIP chunk, 160 M pixels, 7 planes: 4.5 GB
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_AS, &saved), 0);
  std::ifstream status("/proc/self/status");
  std::string line;
  long vm_kb = 0;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) vm_kb = std::stol(line.substr(7));
  rlimit limited = saved;
  limited.rlim_cur = static_cast<rlim_t>(vm_kb + 1024 * 1024) * 1024;  // 1 GB more than now
  ASSERT_EQ(::setrlimit(RLIMIT_AS, &limited), 0);
  const std::string message = read_error(file);
  ::setrlimit(RLIMIT_AS, &saved);
  EXPECT_NE(message.find(file.string() + ": cannot allocate 4.5 GB for 7 planes of 10000000x16 pixels"), std::string::npos)
      << message;
#endif
}

TEST(GBufferErrors, FileCutInsideTheHeader) {
  TempDir dir;
  const fs::path file = dir / "g.exr";
  write_gbuffer(make_gbuffer({0, 0, 7, 7}, false), file);
  fs::resize_file(file, 40);  // magic number intact, header cut short
  const std::string message = read_error(file);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
}

TEST(GBufferErrors, TextFileIsNotAnExr) {
  TempDir dir;
  std::ofstream(dir / "notes.exr") << "P.X P.Y P.Z\nthis is not an image\n";
  const std::string message = read_error(dir / "notes.exr");
  EXPECT_NE(message.find("notes.exr: not an OpenEXR file"), std::string::npos) << message;
}

TEST(GBufferErrors, MissingFile) {
  TempDir dir;
  const std::string message = read_error(dir / "absent.exr");
  EXPECT_NE(message.find("absent.exr: no such file"), std::string::npos) << message;
}

TEST(GBufferErrors, DirectoryIsNotAFile) {
  TempDir dir;
  EXPECT_NE(read_error(dir.path).find("not a regular file"), std::string::npos);
}

TEST(GBufferErrors, WriteIntoMissingDirectoryLeavesNothing) {
  TempDir dir;
  const fs::path file = dir / "no" / "such" / "g.exr";
  try {
    write_gbuffer(make_gbuffer({0, 0, 3, 3}, false), file);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir.path));
}

TEST(GBufferErrors, WrongPlaneSizeIsAProgrammingError) {
  TempDir dir;
  GBuffer g = make_gbuffer({0, 0, 3, 3}, true);
  g.kd[1].pop_back();
  EXPECT_THROW(write_gbuffer(g, dir / "g.exr"), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir / "g.exr"));
}

// One pixel per case, 1 x n, every channel finite and material 0 unless the case says otherwise.
GBuffer pixels(std::size_t n, bool per_pixel) {
  GBuffer g = make_gbuffer({0, 0, static_cast<int>(n) - 1, 0}, per_pixel);
  g.material.assign(n, 0.0f);
  return g;
}

TEST(PixelClassification, EachClass) {
  GBuffer g = pixels(9, true);
  g.material[1] = -1.0f;                                // background
  g.material[2] = -1.0f, g.position[0][2] = kInf;       // background even with P at infinity (a miss)
  g.material[3] = kNaN;                                 // a NaN material is not background
  g.position[1][4] = kNaN;
  g.normal[2][5] = -kInf;
  g.position[0][6] = kNaN, g.normal[0][6] = kNaN;       // position is reported first
  g.kd[1][7] = kNaN;
  g.shininess[8] = kInf;
  const PixelClass expected[] = {PixelClass::shaded,             PixelClass::background,
                                 PixelClass::background,         PixelClass::nonfinite_material,
                                 PixelClass::nonfinite_position, PixelClass::nonfinite_normal,
                                 PixelClass::nonfinite_position, PixelClass::nonfinite_material,
                                 PixelClass::nonfinite_material};
  for (std::size_t i = 0; i < g.pixel_count(); ++i)
    EXPECT_EQ(classify_pixel(g, i), expected[i]) << "pixel " << i;
}

TEST(PixelClassification, NegativeZeroMaterialIsShaded) {
  GBuffer g = pixels(1, false);
  g.material[0] = -0.0f;  // -0 < 0 is false: it is material 0
  EXPECT_EQ(classify_pixel(g, 0), PixelClass::shaded);
}

// The InputError message check_materials throws ("" if none).
std::string material_error(const GBuffer& g, std::size_t material_count) {
  try {
    check_materials(g, material_count);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MaterialCheck, ValidBufferPasses) {
  GBuffer g = make_gbuffer({0, 0, 5, 4}, false);  // materials -1, 0, 1
  g.material[3] = kNaN;                            // not shaded, so not checked here
  EXPECT_EQ(material_error(g, 2), "");
}

TEST(MaterialCheck, OutOfRangeNamesPixelInFileCoordinates) {
  GBuffer g = make_gbuffer({10, 20, 14, 23}, false);
  g.source = "scene_g.exr";
  g.material[2 * 5 + 3] = 7.0f;  // file pixel (13, 22)
  g.material[3 * 5 + 0] = 9.0f;  // a later offender is not the one reported
  EXPECT_EQ(material_error(g, 3), "scene_g.exr: pixel (13, 22): material index 7 out of range (scene has 3 materials)");
  EXPECT_EQ(material_error(g, 10), "");
}

// A table at least as long as one that passed is not checked again; a shorter one is.
TEST(MaterialCheck, RemembersTheShortestTableThatPassed) {
  GBuffer g = pixels(2, false);
  g.material[1] = 2.0f;
  const MaterialCheck check;
  EXPECT_NO_THROW(check.check(g, 4));
  g.material[1] = 9.0f;  // the G-buffer must not change: a table of 4 or more is no longer scanned
  EXPECT_NO_THROW(check.check(g, 6));
  EXPECT_THROW(check.check(g, 3), InputError);  // shorter than any that passed: scanned
  const MaterialCheck known(4);
  EXPECT_NO_THROW(known.check(g, 4));
  EXPECT_THROW(known.check(g, 2), InputError);
}

TEST(MaterialCheck, IndexEqualToCountIsOutOfRange) {
  GBuffer g = pixels(2, false);
  g.material[1] = 2.0f;
  EXPECT_NE(material_error(g, 2).find("pixel (1, 0): material index 2 out of range"), std::string::npos);
}

TEST(MaterialCheck, NonIntegerIndex) {
  GBuffer g = pixels(4, false);
  g.material[2] = 1.5f;
  EXPECT_NE(material_error(g, 3).find("pixel (2, 0): material index 1.5 is not an integer"), std::string::npos)
      << material_error(g, 3);
}

TEST(MaterialCheck, NegativeShininess) {
  GBuffer g = pixels(3, true);
  g.shininess[1] = -4.0f;
  EXPECT_NE(material_error(g, 1).find("pixel (1, 0): shininess -4 is negative"), std::string::npos)
      << material_error(g, 1);
}

TEST(MaterialCheck, TableNotNeededWhenEverythingIsPerPixel) {
  GBuffer g = pixels(3, true);
  for (auto* group : {&g.ka, &g.ks}) *group = g.kd;
  g.material[1] = 5.0f;
  EXPECT_EQ(material_error(g, 0), "");
  g.ks[0].clear(), g.ks[1].clear(), g.ks[2].clear();  // Ks now comes from the table
  EXPECT_NE(material_error(g, 0).find("out of range (scene has 0 materials)"), std::string::npos);
}

}  // namespace
}  // namespace phongcl
