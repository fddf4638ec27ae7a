#include "serve/image_encoding.h"

#include <turbojpeg.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

namespace phongcl {

namespace {

std::string encode_jpeg(const Image& image, const DisplayTransform& display) {
  const std::vector<std::uint8_t> rgbx = display.encode(image);
  const std::unique_ptr<void, int (*)(tjhandle)> compressor(tjInitCompress(), tjDestroy);
  if (!compressor) throw std::runtime_error(std::string("JPEG encoder: ") + tjGetErrorStr());
  unsigned char* jpeg = nullptr;
  unsigned long size = 0;
  if (tjCompress2(compressor.get(), rgbx.data(), image.width, 0, image.height, TJPF_RGBX, &jpeg, &size, TJSAMP_420, 90,
                  TJFLAG_FASTDCT) != 0) {
    tjFree(jpeg);
    throw std::runtime_error(std::string("JPEG encoding failed: ") + tjGetErrorStr2(compressor.get()));
  }
  std::string bytes(reinterpret_cast<const char*>(jpeg), size);
  tjFree(jpeg);
  return bytes;
}

}  // namespace

ImageFormat parse_image_format(std::string_view name) {
  if (name == "png") return ImageFormat::png;
  if (name == "jpeg" || name == "jpg") return ImageFormat::jpeg;
  if (name == "exr") return ImageFormat::exr;
  throw std::invalid_argument("unknown image format '" + std::string(name) + "' (expected png, jpeg or exr)");
}

const char* content_type(ImageFormat format) {
  switch (format) {
    case ImageFormat::png: return "image/png";
    case ImageFormat::jpeg: return "image/jpeg";
    case ImageFormat::exr: return "image/x-exr";
  }
  return "application/octet-stream";
}

Image scale_to_width(const Image& image, int width) {
  if (width < 1 || width > image.width)
    throw std::invalid_argument("width must be in [1, " + std::to_string(image.width) + "] (got " +
                                std::to_string(width) + ")");
  if (width == image.width) return image;
  const int height = std::max(1, static_cast<int>(std::lround(double(image.height) * width / image.width)));
  Image scaled(width, height);
  // Each output pixel averages the input pixels whose index range maps into it (at least one).
  auto span = [](int out, int out_size, int in_size) {
    const int begin = static_cast<int>(static_cast<long long>(out) * in_size / out_size);
    const int end = static_cast<int>(static_cast<long long>(out + 1) * in_size / out_size);
    return std::pair{begin, std::max(end, begin + 1)};
  };
  for (int y = 0; y < height; ++y) {
    const auto [y0, y1] = span(y, height, image.height);
    for (int x = 0; x < width; ++x) {
      const auto [x0, x1] = span(x, width, image.width);
      float* out = scaled.pixel(static_cast<std::size_t>(y) * width + x);
      for (int sy = y0; sy < y1; ++sy)
        for (int sx = x0; sx < x1; ++sx)
          for (int c = 0; c < 4; ++c) out[c] += image.pixel(static_cast<std::size_t>(sy) * image.width + sx)[c];
      const float count = static_cast<float>((y1 - y0) * (x1 - x0));
      for (int c = 0; c < 4; ++c) out[c] /= count;
    }
  }
  return scaled;
}

std::string encode_display_image(const Image& image, ImageFormat format, const DisplayTransform& display) {
  switch (format) {
    case ImageFormat::png: return encode_png(display.encode(image), image.width, image.height);
    case ImageFormat::jpeg: return encode_jpeg(image, display);
    case ImageFormat::exr: break;
  }
  throw std::invalid_argument("encode_display_image: EXR holds linear values, not display bytes");
}

}  // namespace phongcl
