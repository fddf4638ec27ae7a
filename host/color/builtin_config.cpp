#include "color/builtin_config.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <Imath/half.h>

#include "color/chromaticities.h"

namespace phongcl {

namespace OCIO = OCIO_NAMESPACE;

double reinhard_curve(double x) { return x > 0.0 ? (std::isinf(x) ? 1.0 : x / (1.0 + x)) : 0.0; }

double aces_fit_curve(double x) {
  if (!(x > 0.0)) return 0.0;
  if (std::isinf(x)) return 1.0;  // the rational's limit is 2.51 / 2.43, clamped to 1
  return std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

namespace {

// A tone curve as a 1D LUT over every half-float value: OpenColorIO indexes it by the half
// nearest to its float input, so the curve needs no interpolation formula of its own.
OCIO::TransformRcPtr half_domain_curve(double (*curve)(double)) {
  auto lut = OCIO::Lut1DTransform::Create();
  lut->setInputHalfDomain(true);
  lut->setLength(65536);
  for (std::uint32_t bits = 0; bits < 65536; ++bits) {
    half h;
    h.setBits(static_cast<std::uint16_t>(bits));
    const float x = h.isNan() ? 0.0f : static_cast<float>(h);
    const auto y = static_cast<float>(curve(x));
    lut->setValue(bits, y, y, y);
  }
  return lut;
}

// The exact sRGB transfer function (piecewise: a linear toe, then a 2.4 power), encoding.
OCIO::TransformRcPtr srgb_encoding() {
  auto curve = OCIO::ExponentWithLinearTransform::Create();
  curve->setGamma({2.4, 2.4, 2.4, 1.0});
  curve->setOffset({0.055, 0.055, 0.055, 0.0});
  curve->setDirection(OCIO::TRANSFORM_DIR_INVERSE);
  return curve;
}

OCIO::TransformRcPtr clamp_to_unit() {
  auto range = OCIO::RangeTransform::Create();
  range->setMinInValue(0.0);
  range->setMaxInValue(1.0);
  range->setMinOutValue(0.0);
  range->setMaxOutValue(1.0);
  return range;
}

OCIO::TransformRcPtr matrix(const Matrix3& m) {
  auto transform = OCIO::MatrixTransform::Create();
  const double m44[16] = {m[0][0], m[0][1], m[0][2], 0, m[1][0], m[1][1], m[1][2], 0,
                          m[2][0], m[2][1], m[2][2], 0, 0, 0, 0, 1};
  transform->setMatrix(m44);
  return transform;
}

OCIO::TransformRcPtr builtin(const char* style) {
  auto transform = OCIO::BuiltinTransform::Create();
  transform->setStyle(style);
  return transform;
}

OCIO::TransformRcPtr group(std::initializer_list<OCIO::TransformRcPtr> transforms) {
  auto result = OCIO::GroupTransform::Create();
  for (const auto& t : transforms) result->appendTransform(t);
  return result;
}

void add_space(OCIO::ConfigRcPtr& config, const char* name, const char* family, const char* description,
               OCIO::TransformRcPtr to_reference, OCIO::TransformRcPtr from_reference, bool is_data = false) {
  auto space = OCIO::ColorSpace::Create();
  space->setName(name);
  space->setFamily(family);
  space->setDescription(description);
  space->setIsData(is_data);
  if (to_reference) space->setTransform(to_reference, OCIO::COLORSPACE_DIR_TO_REFERENCE);
  if (from_reference) space->setTransform(from_reference, OCIO::COLORSPACE_DIR_FROM_REFERENCE);
  config->addColorSpace(space);
}

}  // namespace

OCIO::ConstConfigRcPtr make_builtin_config() {
  OCIO::ConfigRcPtr config = OCIO::Config::Create();
  config->setName("phongcl built-in");
  config->setDescription("phongcl's built-in config: linear Rec.709 working space; sRGB display with reinhard, aces and clamp views");
  const Matrix3 xyz_to_rec709 = inverse(rgb_to_xyz(kRec709Chromaticities));

  add_space(config, kBuiltinWorkingSpace, "linear", "Scene-linear Rec.709 (sRGB primaries, D65 white): the working space",
            nullptr, nullptr);
  add_space(config, "ACEScg", "linear", "Scene-linear ACES AP1 primaries",
            builtin("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD"), nullptr);
  add_space(config, "ACES2065-1", "linear", "Scene-linear ACES AP0 primaries (the ACES interchange space)",
            group({builtin("UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD"), matrix(xyz_to_rec709)}), nullptr);
  add_space(config, "CIE-XYZ-D65", "linear", "CIE 1931 XYZ, D65 white", matrix(xyz_to_rec709), nullptr);
  auto srgb_decoding = srgb_encoding();
  srgb_decoding->setDirection(OCIO::TRANSFORM_DIR_FORWARD);
  add_space(config, "sRGB", "sRGB", "Rec.709 primaries, sRGB transfer function (8-bit textures, colour pickers)",
            srgb_decoding, nullptr);
  add_space(config, "Raw", "data", "Data that is not colour: never converted", nullptr, nullptr, /*is_data=*/true);

  struct View {
    const char* name;
    const char* space;
    OCIO::TransformRcPtr tone;
    const char* description;
  };
  const View views[] = {
      {"reinhard", "sRGB reinhard", half_domain_curve(reinhard_curve), "x / (1 + x), then sRGB"},
      {"aces", "sRGB aces", half_domain_curve(aces_fit_curve), "Narkowicz's fit of the ACES filmic curve, then sRGB"},
      {"clamp", "sRGB clamp", clamp_to_unit(), "min(x, 1), then sRGB"},
  };
  for (const View& view : views) {
    add_space(config, view.space, "display", view.description, nullptr, group({view.tone, srgb_encoding()}));
    config->addDisplayView("sRGB", view.name, view.space, "");
  }
  config->setActiveDisplays("sRGB");
  config->setActiveViews("reinhard, aces, clamp");

  config->setRole(OCIO::ROLE_REFERENCE, kBuiltinWorkingSpace);
  config->setRole(OCIO::ROLE_SCENE_LINEAR, kBuiltinWorkingSpace);
  config->setRole(OCIO::ROLE_DEFAULT, kBuiltinWorkingSpace);
  config->setRole(OCIO::ROLE_COLOR_PICKING, "sRGB");
  config->setRole(OCIO::ROLE_DATA, "Raw");
  config->setRole(OCIO::ROLE_INTERCHANGE_SCENE, "ACES2065-1");  // states the working space's primaries
  config->validate();
  return config;
}

}  // namespace phongcl
