#pragma once
// Checking text that must be UTF-8 (JSON documents, anything echoed into a JSON message) before a
// library that throws on the first bad byte sees it.
#include <cstddef>
#include <optional>
#include <string_view>

namespace phongcl {

// The offset of the first byte that does not belong to a well-formed UTF-8 sequence (RFC 3629: no
// overlong forms, no surrogates, nothing above U+10FFFF, no truncated sequence), or nullopt.
std::optional<std::size_t> first_invalid_utf8(std::string_view text);

}  // namespace phongcl
