// OpenEXR files read and written by named channel. Headers are parsed by OpenEXR's C++ library,
// after a pass of our own over the attribute sizes; pixels are decoded by its core (C) library,
// which checks every chunk against the file, except for the methods that library cannot decode.
#include "exr/exr_channels.h"

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfStandardAttributes.h>
#include <ImfStdIO.h>
#include <ImfInputPart.h>
#include <ImfMultiPartInputFile.h>
#include <ImfOutputFile.h>
#include <ImfPartType.h>
#include <ImfTestFile.h>
#include <ImfThreading.h>
#include <half.h>
#include <openexr.h>

#include <algorithm>
#include <cctype>
#include <exception>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <type_traits>

#include "common/atomic_file.h"
#include "common/error.h"

namespace phongcl::exr {

namespace {

// Names as OpenEXR's tools spell them, in ExrCompression's order.
constexpr const char* kCompressionNames[] = {"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"};

Imf::Compression to_imf(ExrCompression compression) {
  switch (compression) {
    case ExrCompression::none: return Imf::NO_COMPRESSION;
    case ExrCompression::rle: return Imf::RLE_COMPRESSION;
    case ExrCompression::zips: return Imf::ZIPS_COMPRESSION;
    case ExrCompression::zip: return Imf::ZIP_COMPRESSION;
    case ExrCompression::piz: return Imf::PIZ_COMPRESSION;
    case ExrCompression::pxr24: return Imf::PXR24_COMPRESSION;
    case ExrCompression::b44: return Imf::B44_COMPRESSION;
    case ExrCompression::b44a: return Imf::B44A_COMPRESSION;
    case ExrCompression::dwaa: return Imf::DWAA_COMPRESSION;
    case ExrCompression::dwab: return Imf::DWAB_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}
// A method newer than this list (e.g. HTJ2K) reads fine; outputs then default to ZIP.
ExrCompression from_imf(Imf::Compression compression) {
  for (int i = 0; i < static_cast<int>(std::size(kCompressionNames)); ++i)
    if (to_imf(static_cast<ExrCompression>(i)) == compression) return static_cast<ExrCompression>(i);
  return ExrCompression::zip;
}

Imath::Box2i to_box(const PixelWindow& w) { return {{w.x_min, w.y_min}, {w.x_max, w.y_max}}; }
PixelWindow to_window(const Imath::Box2i& b) { return {b.min.x, b.min.y, b.max.x, b.max.y}; }

// Each chunk costs at least its offset-table entry (8 bytes) and its leader (8 bytes for scanlines,
// 20 for tiles): a file cannot hold more chunks than this allows, whatever its header declares.
constexpr std::uint64_t kMinBytesPerChunk = 16;

// Runs action; an OpenEXR (Iex) or other library exception becomes InputError(file, "what (detail)").
template <class Action>
void translate_errors(const std::filesystem::path& file, const std::string& what, Action&& action) {
  try {
    action();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    std::string detail = e.what();
    std::replace(detail.begin(), detail.end(), '\n', ' ');  // messages are one line
    throw InputError(file, what + " (" + detail + ")");
  }
}

}  // namespace

void set_exr_threads(int threads) { Imf::setGlobalThreadCount(threads); }

const char* compression_name(ExrCompression compression) { return kCompressionNames[static_cast<int>(compression)]; }

ExrCompression parse_compression(const std::string& name) {
  for (int i = 0; i < static_cast<int>(std::size(kCompressionNames)); ++i)
    if (name == kCompressionNames[i]) return static_cast<ExrCompression>(i);
  throw std::invalid_argument("unknown EXR compression '" + name + "' (none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa or dwab)");
}

PixelWindow data_window_for(const PixelWindow& window, int width, int height) {
  if (window.width() <= 0 && window.height() <= 0) return {0, 0, width - 1, height - 1};
  if (window.width() != width || window.height() != height)
    throw std::invalid_argument("data window is " + std::to_string(window.width()) + "x" +
                                std::to_string(window.height()) + " but the pixels are " +
                                std::to_string(width) + "x" + std::to_string(height));
  return window;
}

PixelWindow display_window_for(const PixelWindow& display, const PixelWindow& data) {
  return display.width() <= 0 && display.height() <= 0 ? data : display;
}

// The file as both OpenEXR libraries see it: the C++ library's headers and the core library's
// context, whose chunk reads check every offset, leader and decoded size against the file (the
// C++ reader of OpenEXR 3.1 fills short chunks from whatever its buffers held).
class InputExr::Reader {
 public:
  Reader(const std::filesystem::path& file, std::uint64_t max_pixels) : file_(file) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throw InputError(file, "no such file");
    if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file, "not a regular file");
    if (!std::ifstream(file, std::ios::binary)) throw InputError(file, "cannot open for reading");
    bool tiled = false, deep = false, multi_part = false;
    if (!Imf::isOpenExrFile(file.c_str(), tiled, deep, multi_part))
      throw InputError(file, "not an OpenEXR file");
    if (deep) throw InputError(file, "deep EXR files are not supported");
    check_attribute_sizes();
    open_core();
    translate_errors(file, "truncated or corrupt EXR header",
                     [&] { input_ = std::make_unique<Imf::MultiPartInputFile>(file.c_str()); });
    for (int part = 0; part < input_->parts(); ++part) {
      const Imf::Header& header = input_->header(part);
      if (header.hasType() && Imf::isDeepData(header.type()))
        throw InputError(file, "part " + std::to_string(part) + " holds deep data, which is not supported");
      const std::string prefix = header.hasName() ? header.name() + "." : "";
      for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
        add_channel(it.name(), part, it.name());
        if (!prefix.empty() && std::string(it.name()).rfind(prefix, 0) != 0) add_channel(prefix + it.name(), part, it.name());
      }
    }
    check_declared_size(max_pixels);
  }
  Reader(const Reader&) = delete;  // the core context keeps a pointer to core_error_
  Reader& operator=(const Reader&) = delete;

  const Imf::MultiPartInputFile& input() const { return *input_; }

  std::vector<std::string> channel_names() const {
    std::vector<std::string> names;
    for (const auto& channel : channels_) names.push_back(channel.name);
    return names;
  }
  bool has_channel(const std::string& name) const { return find(name) != nullptr; }

  // Rows [first_row, first_row + row_count) of the data window (row_count < 0: to its end).
  void read(const std::vector<ReadSlice>& slices, int first_row, int row_count) {
    const Imath::Box2i window = input_->header(0).dataWindow();
    Imath::Box2i rows = window;
    rows.min.y = window.min.y + first_row;
    if (row_count >= 0) rows.max.y = std::min(window.max.y, rows.min.y + row_count - 1);
    std::vector<std::vector<NamedSlice>> by_part(static_cast<std::size_t>(input_->parts()));
    for (const auto& slice : slices) {
      const PartChannel* found = find(slice.name);
      if (found == nullptr) throw InputError(file_, "missing channel " + slice.name);
      const Imf::Header& header = input_->header(found->part);
      const Imf::Channel& channel = header.channels()[found->name_in_part];
      if (channel.xSampling != 1 || channel.ySampling != 1)
        throw InputError(file_, "channel " + slice.name + " is subsampled; full resolution is needed");
      if (header.dataWindow() != window)
        throw InputError(file_, "channel " + slice.name + " is in a part whose data window differs from the first part's");
      by_part[found->part].push_back({found->name_in_part, slice});
    }
    for (std::size_t part = 0; part < by_part.size(); ++part) {
      if (by_part[part].empty()) continue;
      const Imf::Compression compression = input_->header(static_cast<int>(part)).compression();
      if (compression == Imf::B44_COMPRESSION || compression == Imf::B44A_COMPRESSION ||
          compression == Imf::DWAA_COMPRESSION || compression == Imf::DWAB_COMPRESSION)
        read_part_with_cpp_library(static_cast<int>(part), by_part[part], window, rows);
      else
        read_part(static_cast<int>(part), by_part[part], window, rows);
    }
  }

 private:
  struct PartChannel {
    std::string name;          // as callers ask for it
    int part;
    std::string name_in_part;  // as the part's header states it
  };

  struct NamedSlice {
    std::string name_in_part;
    ReadSlice slice;
  };

  // One decode pipeline, reused from chunk to chunk of a part.
  struct Decoder {
    exr_decode_pipeline_t pipeline{};  // EXR_DECODE_PIPELINE_INITIALIZER is {0}, which clang warns about
    bool initialized = false;
    exr_const_context_t core;
    ~Decoder() {
      if (initialized) exr_decoding_destroy(core, &pipeline);
    }
  };

  // OpenEXR 3.1's C++ header reader allocates whatever size an attribute declares (gigabytes for a
  // file of a few hundred bytes): every declared size is checked against the bytes that follow it
  // first. Layout: magic and version (8 bytes), then per part attributes "name\0type\0" + int32
  // size + value, each part ending with an empty name (multi-part files end with one more).
  // The bytes OpenEXR 3.1's reader takes for a value of a fixed-size type, whatever size the
  // attribute declares (0: a type it reads by the declared size or by content).
  static std::int64_t fixed_value_size(const std::string& type) {
    static const std::map<std::string, std::int64_t> sizes{
        {"box2i", 16}, {"box2f", 16}, {"compression", 1}, {"lineOrder", 1}, {"envmap", 1}, {"deepImageState", 1},
        {"float", 4}, {"double", 8}, {"int", 4}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12},
        {"v3d", 24}, {"m33f", 36}, {"m33d", 72}, {"m44f", 64}, {"m44d", 128}, {"chromaticities", 32},
        {"keycode", 28}, {"timecode", 8}, {"rational", 8}, {"tiledesc", 9}};
    const auto found = sizes.find(type);
    return found == sizes.end() ? 0 : found->second;
  }

  void check_attribute_sizes() const {
    std::ifstream in(file_, std::ios::binary);
    std::error_code ec;
    const auto bytes = static_cast<std::int64_t>(std::filesystem::file_size(file_, ec));
    char version[8];
    if (ec || !in.read(version, sizeof version)) throw InputError(file_, "truncated or corrupt EXR header");
    const bool multi_part = (static_cast<unsigned char>(version[5]) & 0x10) != 0;  // bit 12 of the version
    const auto read_name = [&] {
      std::string name;
      for (char c; in.get(c) && c != '\0';)
        if (name.size() < 256) name += std::isprint(static_cast<unsigned char>(c)) ? c : '?';  // printable in messages
      if (!in) throw InputError(file_, "truncated or corrupt EXR header");
      return name;
    };
    for (bool part_empty = true;;) {
      const std::string name = read_name();
      if (name.empty()) {
        if (!multi_part || part_empty) return;
        part_empty = true;
        continue;
      }
      part_empty = false;
      const std::string type = read_name();
      std::int32_t size = 0;
      const auto check_size = [&](std::int64_t declared) {
        const std::int64_t left = bytes - static_cast<std::int64_t>(in.tellg());
        if (declared < 0 || declared > left)
          throw InputError(file_, "truncated or corrupt EXR header (attribute '" + name + "' declares " +
                                      std::to_string(declared) + " bytes, " + std::to_string(left) + " are left)");
      };
      if (!in.read(reinterpret_cast<char*>(&size), sizeof size)) throw InputError(file_, "truncated or corrupt EXR header");
      check_size(size);
      // Where the C++ reader goes by content rather than by size, follow it the same way.
      if (const std::int64_t fixed = fixed_value_size(type); fixed > 0) {  // read by type, whatever the size says
        check_size(fixed);
        in.seekg(fixed, std::ios::cur);
      } else if (type == "chlist") {  // channels up to an empty name, 16 bytes after each
        while (!read_name().empty()) in.seekg(16, std::ios::cur);
      } else if (type == "preview") {  // width, height, then 4 bytes per pixel
        std::uint32_t extent[2] = {0, 0};
        if (!in.read(reinterpret_cast<char*>(extent), sizeof extent)) throw InputError(file_, "truncated or corrupt EXR header");
        const std::uint64_t pixels = std::uint64_t{extent[0]} * extent[1];  // exact: two 32-bit factors
        const std::int64_t declared = pixels > std::uint64_t{INT64_MAX} / 4 ? -1 : static_cast<std::int64_t>(4 * pixels);
        check_size(declared);
        in.seekg(declared, std::ios::cur);
      } else {
        in.seekg(size, std::ios::cur);
      }
    }
  }

  void open_core() {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &core_error_;
    // Keep the library's message for ours instead of letting it print to stderr.
    init.error_handler_fn = [](exr_const_context_t context, exr_result_t, const char* message) {
      void* error = nullptr;
      if (exr_get_user_data(context, &error) == EXR_ERR_SUCCESS && error != nullptr)
        *static_cast<std::string*>(error) = message;
    };
    const exr_result_t opened = exr_start_read(&core_, file_.c_str(), &init);
    core_owner_.reset(core_);
    check_core(opened, "truncated or corrupt EXR header");
  }

  void check_core(exr_result_t result, const std::string& what) const {
    if (result == EXR_ERR_SUCCESS) return;
    std::string detail = core_error_.empty() ? exr_get_default_error_message(result) : core_error_;
    std::replace(detail.begin(), detail.end(), '\n', ' ');
    throw InputError(file_, what + " (" + detail + ")");
  }

  void check_declared_size(std::uint64_t max_pixels) const {
    const Imath::Box2i window = input_->header(0).dataWindow();
    const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
    const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    const std::uint64_t pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    if (pixels > max_pixels)
      throw InputError(file_, "declares a " + size + " data window (" + std::to_string(pixels) +
                                  " pixels), more than the limit of " + std::to_string(max_pixels) +
                                  " pixels (--max-pixels)");
    std::uint64_t chunks = 0;
    for (int part = 0; part < input_->parts(); ++part) {
      std::int32_t count = 0;
      check_core(exr_get_chunk_count(core_, part, &count), "truncated or corrupt EXR header");
      chunks += static_cast<std::uint64_t>(count);
    }
    std::error_code ec;
    const std::uint64_t bytes = std::filesystem::file_size(file_, ec);
    if (ec || chunks * kMinBytesPerChunk > bytes)
      throw InputError(file_, "truncated or corrupt EXR: a " + size + " data window needs " + std::to_string(chunks) +
                                  " chunks, more than " + std::to_string(bytes) + " bytes can hold");
  }

  // Calls visit(chunk, x, y) for every level-0 chunk of the part holding one of `rows` (a box of the
  // data window's rows), (x, y) being its first pixel, after the core library has checked its
  // offset and leader against the file.
  template <class Visit>
  void for_each_chunk(int part, const Imath::Box2i& window, const Imath::Box2i& rows, Visit&& visit) const {
    const std::string what = "truncated or corrupt EXR";
    const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
    const auto checked_visit = [&](const exr_chunk_info_t& chunk, std::int64_t x, std::int64_t y) {
      if (x < window.min.x || y < window.min.y || x + chunk.width - 1 > window.max.x || y + chunk.height - 1 > window.max.y)
        throw InputError(file_, what + " (chunk " + std::to_string(chunk.idx) + " lies outside the data window)");
      visit(chunk, x, y);
    };
    exr_chunk_info_t chunk{};
    if (input_->header(part).hasTileDescription()) {
      std::int32_t tile_width = 0, tile_height = 0;
      check_core(exr_get_tile_sizes(core_, part, 0, 0, &tile_width, &tile_height), what);
      if (tile_width <= 0 || tile_height <= 0) throw InputError(file_, what + " (empty tiles)");
      for (std::int64_t ty = (std::int64_t{rows.min.y} - window.min.y) / tile_height;
           ty * tile_height <= std::int64_t{rows.max.y} - window.min.y; ++ty)
        for (std::int64_t tx = 0; tx * tile_width < width; ++tx) {
          check_core(exr_read_tile_chunk_info(core_, part, static_cast<int>(tx), static_cast<int>(ty), 0, 0, &chunk), what);
          checked_visit(chunk, window.min.x + tx * tile_width, window.min.y + ty * tile_height);
        }
      return;
    }
    std::int32_t lines = 0;
    check_core(exr_get_scanlines_per_chunk(core_, part, &lines), what);
    if (lines <= 0) throw InputError(file_, what + " (no scanlines per chunk)");
    for (std::int64_t y = rows.min.y; y <= rows.max.y; y = std::int64_t{chunk.start_y} + lines) {
      check_core(exr_read_scanline_chunk_info(core_, part, static_cast<int>(y), &chunk), what);
      checked_visit(chunk, window.min.x, chunk.start_y);
    }
  }
  // The core library of OpenEXR 3.1 fails on valid B44A and DWA chunks, so these parts are decoded
  // by the C++ reader, after the core has checked every chunk's offset and leader against the file.
  // Its B44 and DWA decoders check their input sizes block by block and section by section.
  void read_part_with_cpp_library(int part, const std::vector<NamedSlice>& slices, const Imath::Box2i& window,
                                  const Imath::Box2i& rows) {
    for_each_chunk(part, window, rows, [](const exr_chunk_info_t&, std::int64_t, std::int64_t) {});
    Imf::FrameBuffer frame_buffer;
    for (const auto& [name, slice] : slices)
      frame_buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, slice.first, rows, slice.stride * sizeof(float)));
    translate_errors(file_, "truncated or corrupt EXR", [&] {
      Imf::InputPart input(*input_, part);
      input.setFrameBuffer(frame_buffer);
      input.readPixels(rows.min.y, rows.max.y);
    });
  }

  // Decodes every level-0 chunk of the part into the slices; a chunk that is missing, short or
  // does not decode to its declared size fails the whole read.
  void read_part(int part, const std::vector<NamedSlice>& slices, const Imath::Box2i& window, const Imath::Box2i& rows) {
    const std::string what = "truncated or corrupt EXR";
    Decoder decoder;
    decoder.core = core_;
    std::vector<std::vector<float>> scratch;  // per slice, one chunk
    const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
    const auto decode = [&](const exr_chunk_info_t& chunk, std::int64_t x, std::int64_t y) {
      exr_decode_pipeline_t& pipeline = decoder.pipeline;
      check_core(decoder.initialized ? exr_decoding_update(core_, part, &chunk, &pipeline)
                                     : exr_decoding_initialize(core_, part, &chunk, &pipeline),
                 what);
      decoder.initialized = true;
      // Each channel is decoded to a plane of its own and then copied: the library's interleaving
      // fast paths (OpenEXR 3.1) put channels in the wrong places when the slices are strided.
      const std::size_t chunk_pixels = static_cast<std::size_t>(chunk.width) * static_cast<std::size_t>(chunk.height);
      scratch.resize(slices.size());
      for (int c = 0; c < pipeline.channel_count; ++c) {
        exr_coding_channel_info_t& channel = pipeline.channels[c];
        channel.decode_to_ptr = nullptr;  // channels nobody asked for are skipped
        for (std::size_t s = 0; s < slices.size(); ++s) {
          if (slices[s].name_in_part != channel.channel_name) continue;
          scratch[s].resize(chunk_pixels);
          channel.decode_to_ptr = reinterpret_cast<std::uint8_t*>(scratch[s].data());
          channel.user_pixel_stride = sizeof(float);
          channel.user_line_stride = static_cast<std::int32_t>(chunk.width * sizeof(float));
          channel.user_bytes_per_element = sizeof(float);
          channel.user_data_type = EXR_PIXEL_FLOAT;
        }
      }
      check_core(exr_decoding_choose_default_routines(core_, part, &pipeline), what);
      check_core(exr_decoding_run(core_, part, &pipeline), what);
      for (std::size_t s = 0; s < slices.size(); ++s) {
        const ReadSlice& slice = slices[s].slice;
        // A chunk may reach beyond the rows asked for: those rows are left out.
        const std::int64_t first = std::max<std::int64_t>(0, rows.min.y - y), last = std::min<std::int64_t>(chunk.height, rows.max.y - y + 1);
        for (std::int64_t row = first; row < last; ++row) {
          const float* from = scratch[s].data() + static_cast<std::size_t>(row) * chunk.width;
          float* to = slice.first + static_cast<std::size_t>((y + row - rows.min.y) * width + (x - window.min.x)) * slice.stride;
          for (std::int32_t i = 0; i < chunk.width; ++i) to[i * slice.stride] = from[i];
        }
      }
    };
    for_each_chunk(part, window, rows, decode);
  }

  void add_channel(const std::string& name, int part, const std::string& name_in_part) {
    if (!has_channel(name)) channels_.push_back({name, part, name_in_part});
  }
  const PartChannel* find(const std::string& name) const {
    for (const auto& channel : channels_)
      if (channel.name == name) return &channel;
    return nullptr;
  }

  std::filesystem::path file_;
  std::unique_ptr<Imf::MultiPartInputFile> input_;
  std::vector<PartChannel> channels_;
  struct CoreFinish {
    void operator()(exr_context_t context) const { exr_finish(&context); }
  };
  std::string core_error_;  // the core library's last message
  std::unique_ptr<std::remove_pointer_t<exr_context_t>, CoreFinish> core_owner_;
  exr_context_t core_ = nullptr;
};

InputExr::InputExr(const std::filesystem::path& file, std::uint64_t max_pixels)
    : reader_(std::make_unique<Reader>(file, max_pixels)) {}
InputExr::~InputExr() = default;

PixelWindow InputExr::data_window() const { return to_window(reader_->input().header(0).dataWindow()); }
PixelWindow InputExr::display_window() const { return to_window(reader_->input().header(0).displayWindow()); }
ExrCompression InputExr::compression() const { return from_imf(reader_->input().header(0).compression()); }
const Imf::Header& InputExr::header(int part) const { return reader_->input().header(part); }
std::vector<std::string> InputExr::channel_names() const { return reader_->channel_names(); }
bool InputExr::has_channel(const std::string& name) const { return reader_->has_channel(name); }
void InputExr::read(const std::vector<ReadSlice>& slices) { reader_->read(slices, 0, -1); }
void InputExr::read_rows(const std::vector<ReadSlice>& slices, int first_row, int row_count) {
  reader_->read(slices, first_row, row_count);
}

namespace {

// One scanline EXR of the slices into `stream`, complete when this returns (the OutputFile writes its
// table of line offsets as it closes).
void write_slices(Imf::OStream& stream, const PixelWindow& data_window, const PixelWindow& display_window,
                  ExrPixelType type, const std::vector<WriteSlice>& slices, ExrCompression compression,
                  const std::optional<Chromaticities>& chromaticities) {
  const Imf::PixelType pixel_type = type == ExrPixelType::half ? Imf::HALF : Imf::FLOAT;
  const Imath::Box2i window = to_box(data_window);
  const std::size_t pixel_count = static_cast<std::size_t>(data_window.width()) * data_window.height();
  // OpenEXR converts file types on reading but not on writing: half channels need half memory.
  std::vector<std::vector<half>> half_planes;
  Imf::FrameBuffer frame_buffer;
  for (const auto& slice : slices) {
    if (pixel_type == Imf::FLOAT) {
      frame_buffer.insert(slice.name, Imf::Slice::Make(Imf::FLOAT, slice.first, window, slice.stride * sizeof(float)));
      continue;
    }
    auto& plane = half_planes.emplace_back(pixel_count);
    for (std::size_t i = 0; i < pixel_count; ++i) plane[i] = half(slice.first[i * slice.stride]);
    frame_buffer.insert(slice.name, Imf::Slice::Make(Imf::HALF, plane.data(), window));
  }
  Imf::Header header(to_box(display_window), window);
  header.compression() = to_imf(compression);
  if (chromaticities) {
    const Chromaticities& c = *chromaticities;
    Imf::addChromaticities(header, Imf::Chromaticities({c.red[0], c.red[1]}, {c.green[0], c.green[1]},
                                                       {c.blue[0], c.blue[1]}, {c.white[0], c.white[1]}));
  }
  for (const auto& slice : slices) header.channels().insert(slice.name, Imf::Channel(pixel_type));
  Imf::OutputFile output(stream, header);
  output.setFrameBuffer(frame_buffer);
  output.writePixels(data_window.height());
}

}  // namespace

void write_channels(const std::filesystem::path& file, const PixelWindow& data_window, const PixelWindow& display_window,
                    ExrPixelType type, const std::vector<WriteSlice>& slices, ExrCompression compression,
                    const std::optional<Chromaticities>& chromaticities) {
  write_atomically(file, [&](const std::filesystem::path& temp) {
    translate_errors(file, "cannot write EXR", [&] {
      Imf::StdOFStream stream(temp.c_str());
      write_slices(stream, data_window, display_window, type, slices, compression, chromaticities);
    });
  });
}

std::string encode_channels(const PixelWindow& data_window, const PixelWindow& display_window, ExrPixelType type,
                            const std::vector<WriteSlice>& slices, ExrCompression compression,
                            const std::optional<Chromaticities>& chromaticities) {
  Imf::StdOSStream stream;
  write_slices(stream, data_window, display_window, type, slices, compression, chromaticities);
  return stream.str();
}

}  // namespace phongcl::exr
