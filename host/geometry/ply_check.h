#pragma once
// A PLY file held against what its header declares, before Assimp reads it.
// Assimp 5.2 aborts on a face without corners (an assert in its triangulation),
// spins on a header cut short, and allocates a list's claimed length before
// reading it. One pass over the bytes, allocating nothing per element, refuses
// each of these: the header must end, name only PLY's types and counts, and
// every element and list must fit in the bytes that follow it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace phongcl {

struct PlyLayout {
  std::vector<std::string> header_lines;  // without their line ends
  std::size_t data_offset = 0;            // where the data starts
  bool binary = false;
  bool crlf = false;            // the header's lines end in "\r\n"
  std::uint64_t vertices = 0;   // the vertex element's count
  std::uint64_t triangles = 0;  // what the faces' corner lists triangulate into
};

// The longest header read: a real one is a few hundred bytes; past this it is
// not a header.
inline constexpr std::size_t kMaxPlyHeaderBytes = std::size_t{1} << 20;

// Throws InputError naming `file` and the first problem: a header without
// end_header, an unknown keyword or type, a count that is not a whole number,
// no vertex x, y and z, an element or list running past the end of the file, a
// face with no corners.
PlyLayout check_ply(std::string_view bytes, const std::filesystem::path& file);

}  // namespace phongcl
