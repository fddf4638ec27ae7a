#include "color/color_conversion.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "color/config_impl.h"
#include "common/error.h"
#include "common/host_threads.h"

namespace phongcl {

namespace OCIO = OCIO_NAMESPACE;

struct ColorConversion::Impl {
  OCIO::ConstProcessorRcPtr processor;
  OCIO::ConstCPUProcessorRcPtr cpu;
};

ColorConversion::ColorConversion(const ColorConfig& config, const std::string& from, const std::string& option,
                                 const std::string& to)
    : impl_(std::make_unique<Impl>()) {
  config.check_color_space(from, option);
  config.check_color_space(to, option);
  try {
    impl_->processor = config.impl().ocio->getProcessor(from.c_str(), to.c_str());
    // Values, not pictures: OpenColorIO's default optimisation approximates logs and powers.
    impl_->cpu = impl_->processor->getOptimizedCPUProcessor(OCIO::OPTIMIZATION_LOSSLESS);
  } catch (const OCIO::Exception& error) {
    std::string message = error.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    throw InputError(option + " '" + from + "': cannot convert to '" + to + "' (" + message + ")");
  }
}

ColorConversion::~ColorConversion() = default;
ColorConversion::ColorConversion(ColorConversion&&) noexcept = default;

bool ColorConversion::is_identity() const { return impl_->processor->isNoOp(); }

glm::dvec3 ColorConversion::operator()(const glm::dvec3& color) const {
  float rgb[3] = {static_cast<float>(color.r), static_cast<float>(color.g), static_cast<float>(color.b)};
  impl_->cpu->applyRGB(rgb);
  return {rgb[0], rgb[1], rgb[2]};
}

void ColorConversion::convert(Planes3& planes) const {
  if (is_identity() || planes[0].empty()) return;
  constexpr std::size_t kChunk = 4096;  // pixels OCIO converts at a time
  for_each_core_range(planes[0].size(), kChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t first = begin; first < end; first += kChunk) {
      const long n = static_cast<long>(std::min(kChunk, end - first));
      OCIO::PlanarImageDesc image(planes[0].data() + first, planes[1].data() + first, planes[2].data() + first, nullptr,
                                  n, 1);
      impl_->cpu->apply(image);
    }
  });
}

namespace {

std::string format_color(const glm::dvec3& c) {
  char text[96];
  std::snprintf(text, sizeof text, "[%.6g, %.6g, %.6g]", c.r, c.g, c.b);
  return text;
}

}  // namespace

void convert_scene_colors(Scene& scene, const ColorConfig& config) {
  if (scene.color_space.empty()) return;
  const ColorConversion conversion(config, scene.color_space, "\"color_space\"");
  const auto convert = [&](glm::dvec3& color, const std::string& what) {
    const glm::dvec3 converted = conversion(color);
    if (converted.r < 0.0 || converted.g < 0.0 || converted.b < 0.0)
      throw InputError(scene.source, what + " " + format_color(color) + " in '" + scene.color_space + "' is " +
                                         format_color(converted) + " in the working space '" + config.working_space() +
                                         "': outside its gamut (negative)");
    color = converted;
  };
  convert(scene.background, "background");
  convert(scene.ambient, "ambient");
  for (std::size_t i = 0; i < scene.lights.size(); ++i) convert(scene.lights[i].color, "lights[" + std::to_string(i) + "].color");
  for (std::size_t i = 0; i < scene.area_lights.size(); ++i)
    convert(scene.area_lights[i].color, "area light " + std::to_string(i) + "'s color");
  // A uniform world's colour; a map's texels are taken as the working space's, as G-buffers are.
  if (scene.environment && scene.environment->file.empty()) convert(scene.environment->color, "the environment's color");
  if (scene.rendered) {
    for (std::size_t i = 0; i < scene.rendered->lights.size(); ++i)
      convert(scene.rendered->lights[i].color, "rendered.lights[" + std::to_string(i) + "].color");
    for (std::size_t i = 0; i < scene.rendered->area_lights.size(); ++i)
      convert(scene.rendered->area_lights[i].color, "rendered area light " + std::to_string(i) + "'s color");
  }
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const std::string name = "materials[" + std::to_string(i) + "].";
    convert(scene.materials[i].ka, name + "ka");
    convert(scene.materials[i].kd, name + "kd");
    convert(scene.materials[i].ks, name + "ks");
  }
  scene.color_space.clear();
}

void convert_gbuffer_colors(GBuffer& gbuffer, const ColorConfig& config, const std::string& space) {
  const ColorConversion conversion(config, space, "--gbuffer-space");
  for (Planes3* planes : {&gbuffer.ka, &gbuffer.kd, &gbuffer.ks, &gbuffer.beauty}) conversion.convert(*planes);
}

}  // namespace phongcl
