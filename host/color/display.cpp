#include "color/display.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "color/byte_steps.h"
#include "color/config_impl.h"
#include "color/display_math.h"
#include "color/display_processor.h"
#include "color/pixel_kernels.h"
#include "color/view_pipeline.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/host_threads.h"
#include "common/joined.h"
#include "image/image.h"  // check_exposure

namespace phongcl {

namespace OCIO = OCIO_NAMESPACE;

namespace {

constexpr std::size_t kBlockPixels = 256;  // stages run over blocks that stay in L1
constexpr std::size_t kRowGrain = 16;  // a core encodes rows in multiples of this

std::shared_ptr<const ViewPipeline> compiled_view(const ColorConfig& config, const std::string& display,
                                                  const std::string& view, const std::string& look) {
  const ColorConfig::Impl& impl = config.impl();
  const auto key = std::make_tuple(display, view, look);
  {
    std::lock_guard lock(impl.mutex);
    if (const auto found = impl.views.find(key); found != impl.views.end()) return found->second;
  }
  OCIO::ConstProcessorRcPtr processor;
  try {
    processor = display_processor(config, display, view, look);
  } catch (const OCIO::Exception& error) {
    std::string message = error.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    throw InputError(impl.description + ": cannot display through view '" + view + "'" +
                     (look.empty() ? "" : " with look '" + look + "'") + ": " + message);
  }
  auto compiled = std::make_shared<const ViewPipeline>(processor);  // outside the lock: milliseconds
  std::lock_guard lock(impl.mutex);
  return impl.views.emplace(key, std::move(compiled)).first->second;
}

// A channel's bytes as a function of its flattened value, the same arithmetic as the loops
// (exposure, clamp, table, byte), as exact byte steps: when the table never decreases over [0, Inf]
// and every negative value has the byte of 0. Else nullptr.
std::shared_ptr<const ByteSteps> byte_steps(const std::vector<float>& table, float scale) {
  constexpr std::uint32_t kInfinityBucket = 0x7f80, kNegativeZeroBucket = 0x8000, kNegativeInfinityBucket = 0xff80;
  for (std::uint32_t b = 0; b < kInfinityBucket; ++b)
    if (!(table[b] <= table[b + 1])) return nullptr;
  const std::uint8_t at_zero = display_byte(table[0]);
  for (std::uint32_t b = kNegativeZeroBucket; b <= kNegativeInfinityBucket; ++b)
    if (display_byte(table[b]) != at_zero) return nullptr;
  constexpr float kMax = std::numeric_limits<float>::max();
  auto steps = ByteSteps::make(
      [&](float v) { return display_byte(table_lookup(table.data(), std::clamp(v * scale, -kMax, kMax))); });
  return steps ? std::make_shared<const ByteSteps>(std::move(*steps)) : nullptr;
}

}  // namespace

DisplayTransform::DisplayTransform(const ColorConfig& config, const DisplaySettings& settings) {
  check_exposure(settings.exposure_stops);
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(settings.background[c])) throw std::invalid_argument("the background colour must be finite");
  display_ = settings.display.empty() ? config.default_display() : settings.display;
  const std::vector<std::string> views = config.views(display_);  // checks the display
  view_ = settings.view.empty() ? config.default_view(display_) : settings.view;
  if (std::find(views.begin(), views.end(), view_) == views.end()) {
    if (const auto left_out = config.omitted_view(display_, view_)) throw InputError(config.description() + ": " + *left_out);
    throw InputError(config.description() + ": display '" + display_ + "' has no view '" + view_ + "' (views: " +
                     joined(views) + ")");
  }
  look_ = settings.look == "None" ? "" : settings.look;
  const std::vector<std::string> looks = config.looks();
  if (!look_.empty() && look_.find(',') == std::string::npos && std::find(looks.begin(), looks.end(), look_) == looks.end())
    throw InputError(config.description() + ": no look '" + look_ + "' (looks: " + (looks.empty() ? "none" : joined(looks)) + ")");
  pipeline_ = compiled_view(config, display_, view_, look_);
  scale_ = static_cast<float>(std::exp2(settings.exposure_stops));
  for (int c = 0; c < 3; ++c) background_[c] = static_cast<float>(settings.background[c]);
  if (const ViewPipeline::Separable* curves = pipeline_->only_table()) {
    for (int c = 0; c < 3; ++c) {
      const auto shared = std::find(curves->table, curves->table + c, curves->table[c]);
      steps_[c] = shared != curves->table + c ? steps_[shared - curves->table] : byte_steps(*curves->table[c], scale_);
    }
    if (!steps_[0] || !steps_[1] || !steps_[2]) steps_[0] = steps_[1] = steps_[2] = nullptr;
  }
}

std::string DisplayTransform::pipeline() const {
  return pipeline_->description() + (steps_[0] ? ", exact byte steps" : "");
}

// The flattening of the loops (color/pixel_kernels.h), unscaled (the steps hold the exposure),
// with the opaque pixels, nearly all of a frame, taken as they are.
void DisplayTransform::encode_by_steps(const Image& image, std::size_t first, std::size_t end, std::uint8_t* out) const {
  const ByteSteps &red = *steps_[0], &green = *steps_[1], &blue = *steps_[2];
  for (std::size_t i = first; i < end; ++i) {
    const float* pixel = image.pixel(i);
    float v[3] = {pixel[0], pixel[1], pixel[2]};
    if (!(pixel[3] >= 1.0f)) {
      const float alpha = pixel[3] > 0.0f ? pixel[3] : 0.0f;  // NaN -> 0
      for (int c = 0; c < 3; ++c) v[c] = (alpha > 0.0f && v[c] == v[c] ? v[c] : 0.0f) + (1.0f - alpha) * background_[c];
    }
    std::uint8_t* bytes = out + 4 * i;
    bytes[0] = red(v[0]);
    bytes[1] = green(v[1]);
    bytes[2] = blue(v[2]);
    bytes[3] = 255;
  }
}

void DisplayTransform::encode_rows(const Image& image, std::size_t first_row, std::size_t rows, std::uint8_t* out) const {
  const std::size_t first = first_row * image.width, end = first + rows * image.width;
  if (steps_[0]) return encode_by_steps(image, first, end, out);
  const PixelKernels& kernels = best_pixel_kernels();
  float r[kBlockPixels], g[kBlockPixels], b[kBlockPixels];
  float* const planes[3] = {r, g, b};
  for (std::size_t block = first; block < end; block += kBlockPixels) {
    const std::size_t count = std::min(kBlockPixels, end - block);
    kernels.flatten(image.pixel(block), count, background_, scale_, planes);
    pipeline_->apply(planes, count, kernels);
    kernels.to_bytes(planes, count, out + 4 * block);
  }
}

std::vector<std::uint8_t> DisplayTransform::encode(const Image& image) const {
  std::vector<std::uint8_t> bytes(4 * image.pixel_count());
  for_each_core_range(static_cast<std::size_t>(image.height), kRowGrain,
                      [&](std::size_t, std::size_t first, std::size_t end) {
                        encode_rows(image, first, end - first, bytes.data());
                      });
  return bytes;
}

void write_png(const Image& image, const std::filesystem::path& file, const DisplayTransform& display) {
  std::string bytes;
  try {
    bytes = encode_png(display.encode(image), image.width, image.height);
  } catch (const std::runtime_error& error) {
    throw InputError(file, std::string("cannot write PNG (") + error.what() + ")");
  }
  write_atomically(file, [&](const std::filesystem::path& temp) {
    std::ofstream stream(temp, std::ios::binary);
    stream.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    stream.close();
    if (!stream) throw InputError(temp, std::string("cannot write PNG: ") + std::strerror(errno));
  });
}

void write_png(const std::filesystem::path& file, const Image& image, const DisplaySettings& settings) {
  static const ColorConfig config = ColorConfig::load();
  write_png(image, file, DisplayTransform(config, settings));
}

}  // namespace phongcl
