#pragma once
// kernels/layout.h seen from the host, with its sizes and offsets checked at compile time: a
// mismatch with the kernel's view would shade silently wrong, so it must not build.
#include <cstddef>

extern "C" {
#include "kernels/layout.h"
}

static_assert(sizeof(PointLight) == 32 && offsetof(PointLight, color) == 16);
static_assert(sizeof(DirectionalLight) == 32 && offsetof(DirectionalLight, color) == 16);
static_assert(sizeof(MaterialRecord) == 64);
static_assert(offsetof(MaterialRecord, ka) == MATERIAL_KA * sizeof(float) &&
              offsetof(MaterialRecord, kd) == MATERIAL_KD * sizeof(float) &&
              offsetof(MaterialRecord, ks) == MATERIAL_KS * sizeof(float) &&
              offsetof(MaterialRecord, shininess) == MATERIAL_SHININESS * sizeof(float));
static_assert(sizeof(LightShape) == 48 && offsetof(LightShape, inverse_range) == 16 && offsetof(LightShape, falloff) == 32);
static_assert(sizeof(LightBounds) == 16 && sizeof(TileGrid) == 16 && sizeof(LinkWord) == 4);
static_assert(sizeof(TileBox) == 32 && offsetof(TileBox, hi) == 16);
