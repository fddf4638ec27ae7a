#pragma once
// Each layout's channel names, stated once, and the detection that picks one from a channel list.
//
// phongcl  position P.X P.Y P.Z; normal N.X N.Y N.Z; material; optional Ka.* Kd.* Ks.* (R G B),
//          shininess. Background only where material < 0.
// blender  <layer>.Position.X/Y/Z; <layer>.Normal.X/Y/Z (world); <layer>.Depth.Z (view-space z);
//          material <layer>.IndexMA.X or <layer>.Material Index.X;
//          kd <layer>.DiffCol.R/G/B or <layer>.Diffuse Color.R/G/B;
//          ks <layer>.GlossCol.R/G/B or <layer>.Glossy Color.R/G/B (not used unless asked: Cycles
//          writes the specular tint, 1 on every Principled surface, not a Phong ks);
//          alpha <layer>.Combined.A or A. A compositor File Output node writes the same passes
//          without the layer, its one-channel passes as .V: Depth.V, IndexMA.V, Alpha.V or Image.A.
// aov      position P or Pworld, normal N or Nworld, each .X/.Y/.Z or .R/.G/.B; depth Z;
//          material; kd diffuse_albedo.R/G/B or albedo.R/G/B; ks specular_albedo.R/G/B; alpha A.
// In blender and aov (and custom) files a zero normal also marks background. The renderer's own
// image, where present: blender <layer>.Combined.R/G/B (File Output: Image.R/G/B); aov
// RGBA.R/G/B, beauty.R/G/B or R G B.
#include <filesystem>
#include <string>
#include <vector>

#include "gbuffer/channel_map.h"
#include "gbuffer/layouts.h"

namespace phongcl {

// One way a file may store a pass.
struct PassSource {
  std::string label;                  // as descriptions name it: "DiffCol", "Pworld"
  std::vector<std::string> channels;  // as many as the pass takes, 1 or 3
};

// The first source whose channels are all present is used.
struct PassSpec {
  Pass pass;
  bool required;
  std::vector<PassSource> sources;
  bool used_by_default = true;  // false: read only when the user asks (ReadOptions::kd/ks)
};

struct LayoutSpec {
  Layout layout = Layout::custom;
  std::string view_layer;                  // blender only
  std::vector<PassSpec> passes;            // in the order descriptions list them
  bool zero_normal_is_background = true;   // renderers leave N = 0 where no surface was hit
  bool file_output = false;                // blender: a compositor File Output node's file
  DepthConvention depth_convention = DepthConvention::distance;
  std::string depth_reason;                // why that convention, for the summary
  // A depth at or beyond this (or not finite) is a centre sample that hit nothing: Cycles writes
  // 1e10, EEVEE 65504. Infinity where the layout has no such value.
  float no_hit_depth;
  // Where the renderer's own image (GBuffer::beauty) may be, in order; never required, and read
  // only when every channel of a source is present.
  std::vector<PassSource> beauty{};
};

// The spec of a preset. For blender an empty view_layer is found from the channels (InputError
// if the file has none, or several and none is called "ViewLayer").
LayoutSpec layout_spec(Layout layout, const std::string& view_layer, const std::vector<std::string>& channels,
                       const std::filesystem::path& file);

// Blender if any channel looks like <layer>.Normal/Position/Depth.*, or is a File Output node's
// Normal.X, Position.X or Depth.V; aov if Pworld/Nworld, an
// .R/.G/.B position or normal, or complete P and N without a material channel; phongcl if there
// is a material channel. Otherwise the user's mapping alone (custom) when there is one, else
// phongcl, whose error then names the channels it misses.
LayoutSpec detect_layout(const std::vector<std::string>& channels, const ReadOptions& options,
                         const std::filesystem::path& file);

}  // namespace phongcl
