#pragma once
// Frames as the bytes an HTTP response carries: PNG and JPEG for display (color/display.h); EXR, for
// the linear values, is image/image.h's encode_exr.
#include <string>
#include <string_view>

#include "color/display.h"
#include "image/image.h"

namespace phongcl {

enum class ImageFormat { png, jpeg, exr };
// Throws std::invalid_argument naming the accepted formats.
ImageFormat parse_image_format(std::string_view name);
const char* content_type(ImageFormat format);

// Box-filtered to `width` pixels wide (height in proportion, at least 1); `width` must be in
// [1, image.width]. The image itself when width == image.width.
Image scale_to_width(const Image& image, int width);

// PNG: 8-bit sRGB RGBA, fast zlib settings. JPEG: RGB (alpha dropped), 4:2:0, quality 90. Throws
// std::runtime_error if an encoder fails. EXR holds linear values: image/image.h's encode_exr.
std::string encode_display_image(const Image& image, ImageFormat format, const DisplayTransform& display);

}  // namespace phongcl
