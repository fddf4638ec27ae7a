#pragma once
// The Blender fixtures of tests/fixtures/blender (made by scripts/blender/make_fixtures.py with
// Blender 3.4: Cycles multilayer, the same passes through a File Output node, EEVEE depth-only, a
// transparent film, and a 4x supersampled Cycles frame with the pixel filter off), and what the
// tests read from them straight through OpenEXR.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer_files.h"
#include "scene/scene.h"

namespace phongcl::testing {

inline const fs::path kFixtures = fs::path(PHONGCL_SOURCE_DIR) / "tests/fixtures/blender";

inline const std::vector<std::string> kCyclesChannels = {
    "ViewLayer.Position.X", "ViewLayer.Position.Y", "ViewLayer.Position.Z", "ViewLayer.Normal.X",
    "ViewLayer.Normal.Y",   "ViewLayer.Normal.Z",   "ViewLayer.Depth.Z",    "ViewLayer.IndexMA.X",
    "ViewLayer.DiffCol.R",  "ViewLayer.DiffCol.G",  "ViewLayer.DiffCol.B",  "ViewLayer.GlossCol.R",
    "ViewLayer.Combined.A"};

inline Scene fixture_scene() { return load_scene(kFixtures / "scene.json"); }

inline glm::dvec3 forward_of(const Camera& c) { return glm::normalize(c.look_at - c.eye); }

// A pixel whose centre sample and whose 8 neighbours' centre samples hit a surface: nothing of the
// sky is inside its 1.5-pixel filter, so its filtered passes are the surface's own.
inline bool fully_covered(const Passes& p, const std::string& depth, int x, int y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = std::clamp(x + dx, 0, p.width - 1), ny = std::clamp(y + dy, 0, p.height - 1);
      if (!(p.at(depth, nx, ny) < 65504.0f)) return false;
    }
  return true;
}

// Every centre sample of the 3x3 neighbourhood on the same material: the filtered colour passes
// hold that material's colours alone.
inline bool one_material(const Passes& p, const std::string& material, int x, int y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = std::clamp(x + dx, 0, p.width - 1), ny = std::clamp(y + dy, 0, p.height - 1);
      if (p.at(material, nx, ny) != p.at(material, x, y)) return false;
    }
  return true;
}

}  // namespace phongcl::testing
