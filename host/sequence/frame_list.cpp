#include "sequence/frame_list.h"

#include <algorithm>
#include <regex>
#include <stdexcept>

namespace phongcl {

namespace {

// Frames of one range, at most this many: a typo such as 1-1000000000 is an error, not a hang.
constexpr long long kMaxFrames = 10'000'000;

std::invalid_argument bad(const std::string& item, const std::string& why) {
  return std::invalid_argument("--frames: '" + item + "' " + why);
}

}  // namespace

std::vector<int> parse_frame_list(const std::string& text) {
  static const std::regex item_syntax(R"((-?\d{1,9})(?:-(-?\d{1,9})(?:x(\d{1,9}))?)?)");
  std::vector<int> frames;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    std::smatch match;
    if (!std::regex_match(item, match, item_syntax))
      throw bad(item, "is not a frame, a range A-B or a stepped range A-BxSTEP");
    const long long first = std::stoll(match[1].str());
    const long long last = match[2].matched ? std::stoll(match[2].str()) : first;
    const long long step = match[3].matched ? std::stoll(match[3].str()) : 1;
    if (last < first) throw bad(item, "ends before it starts");
    if (step < 1) throw bad(item, "has a step below 1");
    if ((last - first) / step + 1 + static_cast<long long>(frames.size()) > kMaxFrames)
      throw bad(item, "has more than " + std::to_string(kMaxFrames) + " frames");
    for (long long frame = first; frame <= last; frame += step) frames.push_back(static_cast<int>(frame));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

}  // namespace phongcl
