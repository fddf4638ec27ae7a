#pragma once
// The Principled BSDF v2's material record (kernels/principled.h; docs/shading.md "Principled v2").
#include "scene/scene.h"
#include "shading/device_layout.h"

namespace phongcl {

// What Cycles' CLOSURE_BSDF_PRINCIPLED_ID (svm/closure.h) derives from the node's inputs before any
// light: the dielectric's index after Specular IOR Level, its tinted F0, the metal's F82-tint B, the
// dielectric's mean Fresnel factor, and the diffuse weight base * (1 - metallic).
void store_principled_v2(MaterialRecord& record, const Material& material);

// Whether the material's diffuse is Cycles' Oren-Nayar: version 2 with a Diffuse Roughness of at least
// 1e-5 (diffuse_roughness_is_almost_zero below it: Lambert's).
bool takes_oren_nayar(const Material& material);

}  // namespace phongcl
