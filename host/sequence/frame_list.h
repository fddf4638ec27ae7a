#pragma once
// --frames: "1001-1240", "1001-1240x4" (every 4th), "1001,1010-1020", or a mix; ascending, each once.
#include <string>
#include <vector>

namespace phongcl {

// Throws std::invalid_argument naming the bad item ("--frames: '10-5' ends before it starts").
std::vector<int> parse_frame_list(const std::string& text);

}  // namespace phongcl
