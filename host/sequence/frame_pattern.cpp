#include "sequence/frame_pattern.h"

#include <algorithm>
#include <cstdio>
#include <regex>
#include <stdexcept>
#include <system_error>

namespace phongcl {

namespace {

struct Placeholder {
  std::size_t position = std::string::npos, length = 0;
  int width = -1;
};

// The run of # or the %[0N]d in text, if any; a second one is an error (which would be the frame?).
Placeholder find_placeholder(const std::string& text) {
  static const std::regex placeholder(R"(#+|%(0?\d*)d)");
  Placeholder found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), placeholder); it != std::sregex_iterator(); ++it) {
    if (found.width >= 0) throw std::invalid_argument("frame pattern '" + text + "' has more than one frame placeholder");
    const std::smatch& match = *it;
    found.position = static_cast<std::size_t>(match.position());
    found.length = static_cast<std::size_t>(match.length());
    found.width = match.str()[0] == '#' ? static_cast<int>(match.length())
                                        : (match[1].length() > 0 ? std::stoi(match[1].str()) : 0);
  }
  if (found.width < 0 && text.find('%') != std::string::npos && std::regex_search(text, std::regex("%[^%]")))
    throw std::invalid_argument("frame pattern '" + text + "': only %d and %0Nd are frame placeholders");
  if (found.width > 9) throw std::invalid_argument("frame pattern '" + text + "' pads frames to more than 9 digits");
  return found;
}

}  // namespace

FramePattern::FramePattern(std::string text) : text_(std::move(text)) {
  const Placeholder found = find_placeholder(text_);
  if (found.width < 0) return;
  width_ = found.width;
  prefix_ = text_.substr(0, found.position);
  suffix_ = text_.substr(found.position + found.length);
}

std::filesystem::path FramePattern::path(int frame) const {
  if (!is_pattern()) return text_;
  char digits[24];
  std::snprintf(digits, sizeof digits, "%0*d", width_, frame);
  return prefix_ + digits + suffix_;
}

std::vector<int> FramePattern::frames_on_disk() const {
  std::vector<int> frames;
  if (!is_pattern()) return frames;
  namespace fs = std::filesystem;
  const fs::path prefix(prefix_);
  // The placeholder sits in the file name, never in a directory: split the name around it.
  const fs::path directory = (prefix_.empty() || prefix_.back() == '/') ? fs::path(prefix_) : prefix.parent_path();
  const std::string name_prefix = (prefix_.empty() || prefix_.back() == '/') ? "" : prefix.filename().string();
  if (suffix_.find('/') != std::string::npos) throw std::invalid_argument("frame pattern '" + text_ + "': the frame must be in the file name");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory.empty() ? fs::path(".") : directory, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= name_prefix.size() + suffix_.size() || name.rfind(name_prefix, 0) != 0 ||
        name.compare(name.size() - suffix_.size(), suffix_.size(), suffix_) != 0)
      continue;
    const std::string digits = name.substr(name_prefix.size(), name.size() - name_prefix.size() - suffix_.size());
    const bool negative = digits[0] == '-';
    if (digits.size() > 10 || digits.size() == static_cast<std::size_t>(negative) ||
        !std::all_of(digits.begin() + negative, digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    const int frame = std::stoi(digits);
    if (path(frame).filename().string() == name) frames.push_back(frame);  // padding as the pattern writes it
  }
  std::sort(frames.begin(), frames.end());
  return frames;
}

}  // namespace phongcl
