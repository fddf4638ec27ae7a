#pragma once
// Reading G-buffers as real renderers write them. A layout says which EXR channels hold which pass
// (see layout_presets.h for each preset's exact channel names); `auto` picks one from the channel
// list, and the user's --channel mapping overrides any pass of it.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gbuffer/channel_map.h"
#include "gbuffer/gbuffer.h"

namespace phongcl {

enum class Layout {
  automatic,  // detect from the channel names
  phongcl,    // P.X P.Y P.Z, N.X N.Y N.Z, material, optional Ka/Kd/Ks/shininess
  blender,    // <view layer>.<pass>.<channel> from Cycles/EEVEE
  aov,        // Arnold/RenderMan-style P, N (or Pworld, Nworld)
  custom,     // nothing recognised: only the user's --channel mapping
};
const char* layout_name(Layout layout);  // "auto", "phongcl", ...
// "auto", "phongcl", "blender" or "aov"; InputError naming the choices otherwise.
Layout parse_layout(std::string_view name);

// What a depth pass measures, for the surface point P seen through a pixel centre:
//   distance  |P - eye|: distance along the ray from the eye.
//   view_z    dot(P - eye, forward): distance along the viewing axis (planar depth, -z of OpenGL
//             view space). Cycles and EEVEE write this.
// The two agree at the image centre and differ by 1/cos(angle off axis) towards the corners.
enum class DepthConvention { distance, view_z };
const char* depth_convention_name(DepthConvention convention);  // "distance" or "viewz", as the flag spells it

// Where kd and ks come from: the layout's choice, the colour pass, or the scene's material table.
enum class ColourSource { layout_default, pass, table };

struct ReadOptions {
  Layout layout = Layout::automatic;
  std::string view_layer;  // blender: empty = the file's only layer (or "ViewLayer" among several)
  ChannelMap channels;     // user mapping; each pass named here replaces the layout's channels
  // Larger data windows are refused before anything is allocated (--max-pixels).
  std::uint64_t max_pixels = std::uint64_t{16384} * 16384;
  std::optional<DepthConvention> depth_convention;  // empty: the layout's
  ColourSource kd = ColourSource::layout_default, ks = ColourSource::layout_default;
  bool beauty = false;  // also read the renderer's own image into gbuffer.beauty, where the file has one
};

struct GBufferRead {
  GBuffer gbuffer;
  Layout layout = Layout::phongcl;  // as detected or given
  // What was used, for the user: "blender (view layer 'ViewLayer': Position, Normal, DiffCol, ...)".
  std::string description;
  // Filled when the file has a depth pass. Without a position pass gbuffer.position is empty and
  // must be reconstructed from depth and the camera (raycast/depth_reconstruction.h) before shading.
  Plane depth;
  DepthConvention depth_convention = DepthConvention::distance;  // the user's, else the layout's
  std::string depth_convention_reason;                           // "Blender's Depth pass is view-space z"
  std::vector<std::string> warnings;                             // for the user: "every pixel has material 0 ..."
  std::string beauty;  // the source of gbuffer.beauty ("Combined"), empty when the file has none
  // A renderer's file without positions: the repair of edges between surfaces (edge_policy.h)
  // compares positions, so it waits for them (positions_from_depth of a GBufferRead runs it).
  bool edges_need_positions = false;

  bool needs_positions_from_depth() const { return gbuffer.position[0].empty(); }
};

// Reads any layout. Background (material -1) is where the material pass says so, where an alpha
// pass is 0, and, in renderer layouts, where the normal is zero or the pixel's centre sample saw the
// sky (depth at the renderer's no-hit value, or a zero position where there is no depth). Renderer
// layouts also fill gbuffer.coverage (see gbuffer.h) and divide the colour passes by it. Without a
// material pass every other pixel gets material 0. Throws InputError naming the file, the missing
// channels and the channels found.
GBufferRead read_gbuffer(const std::filesystem::path& file, const ReadOptions& options);

// The edge repair of a renderer's file (repair_surface_edges), once read.gbuffer has positions;
// says how many pixels it repaired in read.description and clears edges_need_positions.
void repair_edges(GBufferRead& read);

}  // namespace phongcl
