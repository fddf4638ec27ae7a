#include "geometry/mesh_file.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "common/error.h"
#include "common/regular_file.h"
#include "geometry/ply_check.h"

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
// from memory with its header so rewritten; the data is untouched.
std::string with_crlf_header(const PlyLayout& ply, std::string_view bytes) {
  std::string rewritten;
  for (const std::string& line : ply.header_lines) rewritten += line + "\r\n";
  rewritten += bytes.substr(ply.data_offset);
  return rewritten;
}

// The whole file, for the PLY check and Assimp to read from memory.
std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file, "cannot be read");
  return bytes;
}

std::string lowercase_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// Assimp's PLY reader takes a file by its extension or, when no reader claims the extension, by
// "ply" among its first bytes. Every file it could take goes through the PLY check first (a first
// line other than "ply" fails it) and reaches Assimp from memory under the PLY reader's name; a file
// of another extension goes to that extension's reader, and one of an extension no reader claims
// is refused (read_mesh), so that no unchecked file reaches the PLY reader.
bool read_as_ply(const std::filesystem::path& file) {
  char magic[3] = {};
  std::ifstream(file, std::ios::binary).read(magic, sizeof magic);
  return lowercase_extension(file) == ".ply" || std::string_view(magic, sizeof magic) == "ply";
}

}  // namespace

TriangleMesh read_mesh(const std::filesystem::path& file) {
  require_regular_file(file, "mesh");
  Assimp::Importer importer;
  // Points and lines are sorted out and removed; polygons become triangles; the file's node
  // hierarchy is flattened into its meshes' vertices. Validation first: a file Assimp misreads is
  // an error naming it, not a crash in a later step.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned steps = aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_SortByPType |
                         aiProcess_PreTransformVertices;
  const aiScene* scene = nullptr;
  if (read_as_ply(file)) {
    std::string bytes = file_bytes(file);
    const PlyLayout ply = check_ply(bytes, file);
    const bool data_starts_with_newline = ply.data_offset < bytes.size() && bytes[ply.data_offset] == '\n';
    if (ply.binary && !ply.crlf && data_starts_with_newline) bytes = with_crlf_header(ply, bytes);
    scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), steps, "ply");
  } else {
    const std::string extension = lowercase_extension(file);
    if (extension.empty() || !importer.IsExtensionSupported(extension))
      throw InputError(file, "cannot read the mesh: '" + extension +
                                 "' is not a mesh format Assimp reads (PLY, OBJ, glTF, ...), and it is not a PLY file");
    scene = importer.ReadFile(file.string(), steps);
  }
  if (scene == nullptr) throw InputError(file, one_line(importer.GetErrorString()));
  TriangleMesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) append_triangles(*scene->mMeshes[m], file, mesh);
  if (mesh.triangles.empty()) throw InputError(file, "has no triangles");
  return mesh;
}

MeshCounts count_mesh(const std::filesystem::path& file) {
  require_regular_file(file, "mesh");
  if (read_as_ply(file)) {
    const PlyLayout ply = check_ply(file_bytes(file), file);
    return {ply.vertices, ply.triangles};
  }
  const TriangleMesh mesh = read_mesh(file);
  return {mesh.vertices.size(), mesh.triangles.size()};
}

}  // namespace phongcl
