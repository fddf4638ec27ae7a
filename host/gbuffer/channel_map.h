#pragma once
// What an EXR channel means to phongcl: the G-buffer passes, and the user's own mapping of
// channels to passes (`--channel position=Foo.X,Foo.Y,Foo.Z`).
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace phongcl {

enum class Pass {
  position,   // 3 channels: x, y, z
  normal,     // 3 channels, any length; zero marks background in renderer layouts
  depth,      // 1 channel, stands in for position (see raycast/depth_reconstruction.h)
  material,   // 1 channel: index into the scene's materials
  alpha,      // 1 channel: 0 marks background
  ka, kd, ks, // 3 channels each: per-pixel material colours
  shininess,  // 1 channel
};

const char* pass_name(Pass pass);  // "position", as --channel spells it

// Pass -> EXR channel names, as many as the pass takes (1 or 3), in x/y/z (r/g/b) order.
using ChannelMap = std::map<Pass, std::vector<std::string>>;

// Parses one `--channel` value, "position=Foo.X,Foo.Y,Foo.Z" or "material=Foo.index". Throws
// InputError naming the value for an unknown pass or the wrong number of channels.
std::pair<Pass, std::vector<std::string>> parse_channel_assignment(std::string_view text);

}  // namespace phongcl
