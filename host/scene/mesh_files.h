#pragma once
// The mesh files a scene's objects name: inputs that no output may replace (refuse_shared_files),
// and what a server holding the scene must read again when they change.
#include <filesystem>
#include <vector>

#include "common/same_file.h"
#include "scene/scene.h"

namespace phongcl {

// Each mesh file `objects` name, transforms' children included, once, in the order first named.
std::vector<std::filesystem::path> mesh_files(const std::vector<Object>& objects);

// One of them as an input for refuse_shared_files, labelled "the scene's mesh".
NamedFile mesh_input(const std::filesystem::path& file);

}  // namespace phongcl
