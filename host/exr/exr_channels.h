#pragma once
// OpenEXR plumbing shared by the G-buffer and image files: open with clear errors, read named
// channels into float memory, write named float channels. The exr room: both the gbuffer and the
// image rooms read and write through it.
#include <ImfHeader.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "exr/pixel_window.h"

namespace phongcl::exr {

// OpenEXR's (de)compression runs on its global thread pool; every file opened afterwards uses
// `threads` of them (0: on the calling thread only).
void set_exr_threads(int threads);

// Names as OpenEXR's tools spell them ("none", "zip", "dwab", ...).
const char* compression_name(ExrCompression compression);
// Throws std::invalid_argument naming the choices.
ExrCompression parse_compression(const std::string& name);

// The data window to write. Buffers built in memory (not read from a file) may leave it unset,
// which means "at the origin"; a set one must match the pixel arrays.
PixelWindow data_window_for(const PixelWindow& window, int width, int height);
// The display window to write: the data window where none is set.
PixelWindow display_window_for(const PixelWindow& display, const PixelWindow& data);

// Where one channel's floats live: data-window pixel (x, y) is at
// first[((y - y_min) * width + (x - x_min)) * stride]. stride 1 = a plane, 4 = interleaved RGBA.
template <class Float>
struct ChannelSlice {
  std::string name;
  Float* first;
  std::size_t stride = 1;
};
using ReadSlice = ChannelSlice<float>;
using WriteSlice = ChannelSlice<const float>;

// The most pixels a file may declare before anything is allocated (--max-pixels): 16384 x 16384.
// A G-buffer is up to 16 float planes, so this already asks for 17 GB.
inline constexpr std::uint64_t kDefaultMaxPixels = std::uint64_t{16384} * 16384;

// A flat (not deep) EXR opened for reading: single- or multi-part, scanline or tiled parts alike.
// Channels are named as the parts state them; a channel of a named part is also reachable as
// "<part name>.<channel>" (Nuke and others write one part per layer with unprefixed channels).
// Where two parts hold the same name, the first part's channel is the one read.
// Every error is an InputError naming the file.
class InputExr {
 public:
  // Throws when the data window has more than max_pixels pixels or more chunks than the file's
  // size can hold: nothing the size of the declared window is allocated before that.
  explicit InputExr(const std::filesystem::path& file, std::uint64_t max_pixels = kDefaultMaxPixels);
  ~InputExr();
  InputExr(const InputExr&) = delete;
  InputExr& operator=(const InputExr&) = delete;

  // Of the first part; parts whose channels are read together must share it (see read()).
  PixelWindow data_window() const;
  PixelWindow display_window() const;
  ExrCompression compression() const;
  const Imf::Header& header(int part) const;

  // In file order, part by part.
  std::vector<std::string> channel_names() const;
  bool has_channel(const std::string& name) const;

  // Reads the named channels (which must exist, at full resolution) as float, converting half and
  // uint. A chunk that is missing, short or does not decode to its declared size fails the read.
  void read(const std::vector<ReadSlice>& slices);
  // The same for rows [first_row, first_row + row_count) of the data window only (0 is its top
  // row), into slices of row_count x width pixels: a large image a block of rows at a time.
  void read_rows(const std::vector<ReadSlice>& slices, int first_row, int row_count);

 private:
  class Reader;  // exr_channels.cpp: the C++ and core libraries' views of the file
  std::unique_ptr<Reader> reader_;
};

// Writes the slices as one scanline EXR, atomically (temp file, then rename), with the
// chromaticities attribute when they are given.
void write_channels(const std::filesystem::path& file, const PixelWindow& data_window,
                    const PixelWindow& display_window, ExrPixelType type, const std::vector<WriteSlice>& slices,
                    ExrCompression compression = ExrCompression::zip,
                    const std::optional<Chromaticities>& chromaticities = std::nullopt);
// The same EXR as bytes in memory (for an HTTP response), with no file in between.
std::string encode_channels(const PixelWindow& data_window, const PixelWindow& display_window, ExrPixelType type,
                            const std::vector<WriteSlice>& slices, ExrCompression compression = ExrCompression::zip,
                            const std::optional<Chromaticities>& chromaticities = std::nullopt);

}  // namespace phongcl::exr
