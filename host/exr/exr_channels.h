#pragma once
// OpenEXR plumbing shared by the G-buffer and image files: open with clear errors, read named
// channels into float memory, write named float channels. The exr room: both the gbuffer and the
// image rooms read and write through it.
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputPart.h>
#include <ImfMultiPartInputFile.h>
#include <ImfOutputFile.h>
#include <ImfPartType.h>
#include <ImfTestFile.h>
#include <half.h>

#include <algorithm>
#include <cstddef>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "exr/pixel_window.h"

namespace phongcl::exr {

inline Imath::Box2i to_box(const PixelWindow& w) { return {{w.x_min, w.y_min}, {w.x_max, w.y_max}}; }
inline PixelWindow to_window(const Imath::Box2i& b) { return {b.min.x, b.min.y, b.max.x, b.max.y}; }

// The data window to write. Buffers built in memory (not read from a file) may leave it unset,
// which means "at the origin"; a set one must match the pixel arrays.
inline PixelWindow data_window_for(const PixelWindow& window, int width, int height) {
  if (window.width() <= 0 && window.height() <= 0) return {0, 0, width - 1, height - 1};
  if (window.width() != width || window.height() != height)
    throw std::invalid_argument("data window is " + std::to_string(window.width()) + "x" +
                                std::to_string(window.height()) + " but the pixels are " +
                                std::to_string(width) + "x" + std::to_string(height));
  return window;
}
inline PixelWindow display_window_for(const PixelWindow& display, const PixelWindow& data) {
  return display.width() <= 0 && display.height() <= 0 ? data : display;
}

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

// A flat (not deep) EXR opened for reading: single- or multi-part, scanline or tiled parts alike.
// Channels are named as the parts state them; a channel of a named part is also reachable as
// "<part name>.<channel>" (Nuke and others write one part per layer with unprefixed channels).
// Where two parts hold the same name, the first part's channel is the one read.
class InputExr {
 public:
  explicit InputExr(const std::filesystem::path& file) : file_(file) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throw InputError(file, "no such file");
    if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file, "not a regular file");
    if (!std::ifstream(file, std::ios::binary)) throw InputError(file, "cannot open for reading");
    bool tiled = false, deep = false, multi_part = false;
    if (!Imf::isOpenExrFile(file.c_str(), tiled, deep, multi_part))
      throw InputError(file, "not an OpenEXR file");
    if (deep) throw InputError(file, "deep EXR files are not supported");
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
  }

  // Of the first part; parts whose channels are read together must share it (see read()).
  PixelWindow data_window() const { return to_window(input_->header(0).dataWindow()); }
  PixelWindow display_window() const { return to_window(input_->header(0).displayWindow()); }
  int parts() const { return input_->parts(); }

  // In file order, part by part.
  std::vector<std::string> channel_names() const {
    std::vector<std::string> names;
    for (const auto& channel : channels_) names.push_back(channel.name);
    return names;
  }
  bool has_channel(const std::string& name) const { return find(name) != nullptr; }

  // Reads the named channels (which must exist) as float, converting half and uint.
  void read(const std::vector<ReadSlice>& slices) {
    const Imath::Box2i window = input_->header(0).dataWindow();
    std::vector<Imf::FrameBuffer> frame_buffers(static_cast<std::size_t>(input_->parts()));
    std::vector<bool> used(frame_buffers.size(), false);
    for (const auto& slice : slices) {
      const PartChannel* found = find(slice.name);
      if (found == nullptr) throw InputError(file_, "missing channel " + slice.name);
      const Imf::Header& header = input_->header(found->part);
      const Imf::Channel& channel = header.channels()[found->name_in_part];
      if (channel.xSampling != 1 || channel.ySampling != 1)
        throw InputError(file_, "channel " + slice.name + " is subsampled; full resolution is needed");
      if (header.dataWindow() != window)
        throw InputError(file_, "channel " + slice.name + " is in a part whose data window differs from the first part's");
      frame_buffers[found->part].insert(
          found->name_in_part, Imf::Slice::Make(Imf::FLOAT, slice.first, window, slice.stride * sizeof(float)));
      used[found->part] = true;
    }
    translate_errors(file_, "truncated or corrupt EXR", [&] {
      for (std::size_t part = 0; part < frame_buffers.size(); ++part) {
        if (!used[part]) continue;
        Imf::InputPart input(*input_, static_cast<int>(part));
        input.setFrameBuffer(frame_buffers[part]);
        input.readPixels(window.min.y, window.max.y);
      }
    });
  }

 private:
  struct PartChannel {
    std::string name;          // as callers ask for it
    int part;
    std::string name_in_part;  // as the part's header states it
  };

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
};

// Writes the slices as one scanline EXR with ZIP compression, atomically (temp file, then rename).
inline void write_channels(const std::filesystem::path& file, const PixelWindow& data_window,
                           const PixelWindow& display_window, ExrPixelType type,
                           const std::vector<WriteSlice>& slices) {
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
  write_atomically(file, [&](const std::filesystem::path& temp) {
    translate_errors(file, "cannot write EXR", [&] {
      Imf::Header header(to_box(display_window), window);
      header.compression() = Imf::ZIP_COMPRESSION;
      for (const auto& slice : slices) header.channels().insert(slice.name, Imf::Channel(pixel_type));
      Imf::OutputFile output(temp.c_str(), header);
      output.setFrameBuffer(frame_buffer);
      output.writePixels(data_window.height());
    });
  });
}

}  // namespace phongcl::exr
