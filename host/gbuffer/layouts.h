#pragma once
// Reading G-buffers as real renderers write them. A layout says which EXR channels hold which pass
// (see layout_presets.h for each preset's exact channel names); `auto` picks one from the channel
// list, and the user's --channel mapping overrides any pass of it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

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

struct ReadOptions {
  Layout layout = Layout::automatic;
  std::string view_layer;  // blender: empty = the file's only layer (or "ViewLayer" among several)
  ChannelMap channels;     // user mapping; each pass named here replaces the layout's channels
  // Larger data windows are refused before anything is allocated (--max-pixels).
  std::uint64_t max_pixels = std::uint64_t{16384} * 16384;
};

struct GBufferRead {
  GBuffer gbuffer;
  Layout layout = Layout::phongcl;  // as detected or given
  // What was used, for the user: "blender (view layer 'ViewLayer': Position, Normal, DiffCol, ...)".
  std::string description;
  // Filled only when the file has depth but no position: gbuffer.position is then empty and must
  // be reconstructed from it and the camera (raycast/depth_reconstruction.h) before shading.
  Plane depth;

  bool needs_positions_from_depth() const { return gbuffer.position[0].empty(); }
};

// Reads any layout. Background (material -1) is where the material pass says so, where an alpha
// pass is 0, and, in renderer layouts, where the normal is zero. Without a material pass every
// other pixel gets material 0. Throws InputError naming the file, the missing channels and the
// channels found.
GBufferRead read_gbuffer(const std::filesystem::path& file, const ReadOptions& options);

}  // namespace phongcl
