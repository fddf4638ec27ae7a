#include "scene/mesh_files.h"

#include <algorithm>

namespace phongcl {

namespace {

void add_mesh_files(const std::vector<Object>& objects, std::vector<std::filesystem::path>& files) {
  for (const Object& object : objects) {
    if (object.kind == Object::Kind::mesh && std::find(files.begin(), files.end(), object.file) == files.end())
      files.push_back(object.file);
    add_mesh_files(object.children, files);
  }
}

}  // namespace

std::vector<std::filesystem::path> mesh_files(const std::vector<Object>& objects) {
  std::vector<std::filesystem::path> files;
  add_mesh_files(objects, files);
  return files;
}

NamedFile mesh_input(const std::filesystem::path& file) { return {"the scene's mesh", file}; }

}  // namespace phongcl
