#include "geometry/mesh_file.h"

#include <cmath>
#include <fstream>
#include <iterator>
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

// Assimp 5.2's PLY reader skips a '\n' that starts a binary file's data as if it ended the header
// line, and reads every value one byte off (assimp/assimp#5341; one binary PLY in 256). With the
// header's lines ended by "\r\n" it takes exactly those two bytes, so such a file is handed over
// from memory with its header so rewritten; the data is untouched. Empty when the file needs none.
std::vector<char> ply_with_crlf_header(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string header;
  for (std::string line; header.size() < 65536 && std::getline(in, line);) {
    header += line + '\n';
    if (line == "end_header") break;
  }
  if (!header.starts_with("ply\n") || !header.ends_with("\nend_header\n") ||
      header.find("\nformat binary") == std::string::npos || in.peek() != '\n')
    return {};
  std::vector<char> rewritten;
  for (char c : header) {
    if (c == '\n') rewritten.push_back('\r');
    rewritten.push_back(c);
  }
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
  const std::vector<char> rewritten = ply_with_crlf_header(file);
  const aiScene* scene = rewritten.empty() ? importer.ReadFile(file.string(), steps)
                                           : importer.ReadFileFromMemory(rewritten.data(), rewritten.size(), steps, "ply");
  if (scene == nullptr) throw InputError(file, one_line(importer.GetErrorString()));
  TriangleMesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) append_triangles(*scene->mMeshes[m], file, mesh);
  if (mesh.triangles.empty()) throw InputError(file, "has no triangles");
  return mesh;
}

}  // namespace phongcl
