#include "shading/pack_environment_specular.h"

#include <algorithm>
#include <cmath>

namespace phongcl {

namespace {

// The distinct lobes that get maps, in the materials' order, at most kMaxEnvironmentLobes.
std::vector<SpecularLobe> mapped_lobes(const Scene& scene) {
  std::vector<SpecularLobe> lobes;
  for (const Material& material : scene.materials) {
    const SpecularLobe lobe = environment_lobe(material);
    if (lobes.size() < static_cast<std::size_t>(kMaxEnvironmentLobes) && std::find(lobes.begin(), lobes.end(), lobe) == lobes.end())
      lobes.push_back(lobe);
  }
  return lobes;
}

// The mapped lobe a lobe reads: itself, or the nearest in width.
std::size_t map_of(const std::vector<SpecularLobe>& mapped, const SpecularLobe& lobe) {
  if (const auto found = std::find(mapped.begin(), mapped.end(), lobe); found != mapped.end())
    return static_cast<std::size_t>(found - mapped.begin());
  const double width = lobe_width(lobe);
  std::size_t nearest = 0;
  for (std::size_t k = 1; k < mapped.size(); ++k)
    if (std::abs(lobe_width(mapped[k]) - width) < std::abs(lobe_width(mapped[nearest]) - width)) nearest = k;
  return nearest;
}

}  // namespace

SpecularLobe environment_lobe(const Material& material) {
  switch (material.specular_model) {
    case SpecularModel::phong:
      return {SpecularLobe::Kind::phong, material.shininess, false};
    case SpecularModel::phong_normalized:
      return {SpecularLobe::Kind::phong, material.shininess, true};
    case SpecularModel::blinn_phong:
      return {SpecularLobe::Kind::blinn, material.shininess, false};
    case SpecularModel::blinn_phong_normalized:
      return {SpecularLobe::Kind::blinn, material.shininess, true};
    case SpecularModel::principled:
      break;
  }
  return {SpecularLobe::Kind::ggx, material.roughness * material.roughness, true};
}

std::size_t environment_lobe_bytes(const Scene& scene) {
  std::size_t bytes = scene.materials.size() * sizeof(EnvironmentLobe);
  for (const SpecularLobe& lobe : mapped_lobes(scene)) {
    const std::size_t height = static_cast<std::size_t>(prefiltered_height(lobe));
    bytes += 3 * 2 * height * height * sizeof(layout_float);
  }
  return bytes;
}

void pack_environment_lobes(PackedEnvironment& packed, const Scene& scene, const std::shared_ptr<const IrradianceMap>& map) {
  const std::vector<SpecularLobe> mapped = mapped_lobes(scene);
  std::vector<EnvironmentLobe> maps;
  for (const SpecularLobe& lobe : mapped) {
    const std::shared_ptr<const RadianceGrid> prefiltered = prefiltered_of(map, lobe);
    EnvironmentLobe record{};
    record.offset = static_cast<layout_uint>(packed.texels.size());
    record.width = prefiltered->width;
    record.height = prefiltered->height;
    packed.texels.insert(packed.texels.end(), prefiltered->rgb.begin(), prefiltered->rgb.end());
    maps.push_back(record);
  }
  for (const Material& material : scene.materials) {
    const SpecularLobe lobe = environment_lobe(material);
    EnvironmentLobe record = maps[map_of(mapped, lobe)];
    record.amplitude = static_cast<float>(lobe_integral(lobe));
    record.split_sum = lobe.kind == SpecularLobe::Kind::ggx;
    record.takes_cosine = lobe.takes_cosine && !record.split_sum;
    record.half_vector = lobe.kind == SpecularLobe::Kind::blinn;
    record.spread = static_cast<float>(lobe_width(lobe));
    packed.lobes.push_back(record);
  }
}

}  // namespace phongcl
