#include "geometry/mesh_file.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "common/error.h"

namespace phongcl {
namespace {

// Assimp's messages may span lines; the user gets one.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text.empty() ? "cannot be read as a mesh" : text;
}

void append_triangles(const aiMesh& mesh, const std::filesystem::path& file, TriangleMesh& out) {
  const auto base = static_cast<std::uint32_t>(out.vertices.size());
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    const aiVector3D& v = mesh.mVertices[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw InputError(file, "vertex " + std::to_string(out.vertices.size()) + " is not finite");
    out.vertices.emplace_back(v.x, v.y, v.z);
  }
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines cast no shadow
    std::array<std::uint32_t, 3> corners{};
    for (int k = 0; k < 3; ++k) {
      if (face.mIndices[k] >= mesh.mNumVertices)
        throw InputError(file, "face " + std::to_string(f) + " refers to a vertex that is not there");
      corners[k] = base + face.mIndices[k];
    }
    if (out.triangles.size() == kMaxMeshTriangles)
      throw InputError(file, "has more than " + std::to_string(kMaxMeshTriangles) + " triangles");
    out.triangles.push_back(corners);
  }
}

// A PLY file's header: its lines up to "end_header", and where its data starts. Empty lines when
// the file is not a PLY file (Assimp then reads it by its own lights).
struct PlyHeader {
  std::vector<std::string> lines;  // without their line ends
  std::uintmax_t data_offset = 0;
  bool crlf = false;  // lines end in "\r\n"
  bool binary() const { return lines.size() > 1 && lines[1].starts_with("format binary"); }
};

PlyHeader read_ply_header(std::ifstream& in) {
  PlyHeader header;
  std::uintmax_t bytes = 0;
  for (std::string line; bytes < 65536 && std::getline(in, line);) {
    bytes += line.size() + 1;
    header.crlf = !line.empty() && line.back() == '\r';
    if (header.crlf) line.pop_back();
    if (header.lines.empty() && line != "ply") return {};
    header.lines.push_back(line);
    if (line == "end_header") {
      header.data_offset = bytes;
      return header;
    }
  }
  return {};
}

// The fewest bytes a PLY file's data can take for the elements its header declares (a binary
// value's size, or two characters for an ASCII one; a list at least its count), so that a header
// declaring billions of vertices in a small file is refused before Assimp allocates for them.
std::uintmax_t least_data_bytes(const PlyHeader& header) {
  static const std::map<std::string, unsigned> kSizes = {
      {"char", 1},  {"uchar", 1},  {"int8", 1},  {"uint8", 1},  {"short", 2},   {"ushort", 2},  {"int16", 2},
      {"uint16", 2}, {"int", 4},   {"uint", 4},  {"int32", 4},  {"uint32", 4},  {"float", 4},   {"float32", 4},
      {"double", 8}, {"float64", 8}};
  long double total = 0, count = 0, record = 0;
  for (const std::string& line : header.lines) {
    std::istringstream words(line);
    std::string keyword, type;
    words >> keyword;
    if (keyword == "element") {
      total += count * record;
      std::string name;
      words >> name >> count;
      record = 0;
    } else if (keyword == "property") {
      words >> type;
      if (type == "list") words >> type;  // the count's type: a list holds at least its count
      const auto size = kSizes.find(type);
      record += header.binary() ? (size == kSizes.end() ? 1 : size->second) : 2;
    }
  }
  total += count * record;
  return total > static_cast<long double>(std::numeric_limits<std::uintmax_t>::max()) ? std::numeric_limits<std::uintmax_t>::max()
                                                                                      : static_cast<std::uintmax_t>(total);
}

// Assimp 5.2's PLY reader skips a '\n' that starts a binary file's data as if it ended the header
// line, and reads every value one byte off (assimp/assimp#5341; one binary PLY in 256). With the
// header's lines ended by "\r\n" it takes exactly those two bytes, so such a file is handed over
// from memory with its header so rewritten; the data is untouched.
std::vector<char> with_crlf_header(const PlyHeader& header, std::ifstream& in) {
  std::vector<char> rewritten;
  for (const std::string& line : header.lines) {
    rewritten.insert(rewritten.end(), line.begin(), line.end());
    rewritten.push_back('\r');
    rewritten.push_back('\n');
  }
  in.seekg(static_cast<std::streamoff>(header.data_offset));
  rewritten.insert(rewritten.end(), std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return rewritten;
}

}  // namespace

TriangleMesh read_mesh(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) throw InputError(file, "cannot open (no such mesh file)");
  Assimp::Importer importer;
  // Points and lines are sorted out and removed; polygons become triangles; the file's node
  // hierarchy is flattened into its meshes' vertices. Validation first: a file Assimp misreads is
  // an error naming it, not a crash in a later step.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned steps = aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_SortByPType |
                         aiProcess_PreTransformVertices;
  std::ifstream in(file, std::ios::binary);
  const PlyHeader header = read_ply_header(in);
  std::vector<char> rewritten;
  if (!header.lines.empty()) {
    const std::uintmax_t size = std::filesystem::file_size(file, error);
    const std::uintmax_t least = least_data_bytes(header);
    if (!error && least > size - header.data_offset)
      throw InputError(file, "its header declares elements that need at least " + std::to_string(least) +
                                 " bytes, but only " + std::to_string(size - header.data_offset) + " follow it");
    in.clear();
    in.seekg(static_cast<std::streamoff>(header.data_offset));
    if (header.binary() && !header.crlf && in.peek() == '\n') rewritten = with_crlf_header(header, in);
  }
  const aiScene* scene = rewritten.empty() ? importer.ReadFile(file.string(), steps)
                                           : importer.ReadFileFromMemory(rewritten.data(), rewritten.size(), steps, "ply");
  if (scene == nullptr) throw InputError(file, one_line(importer.GetErrorString()));
  TriangleMesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) append_triangles(*scene->mMeshes[m], file, mesh);
  if (mesh.triangles.empty()) throw InputError(file, "has no triangles");
  return mesh;
}

}  // namespace phongcl
