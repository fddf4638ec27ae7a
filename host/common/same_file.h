#pragma once
// Refusing a run whose outputs would replace its own inputs (or each other) before anything is
// read: every front end lists the files it reads and writes, each with the option that named it.
#include <filesystem>
#include <string>
#include <vector>

namespace phongcl {

struct NamedFile {
  std::string option;          // "--out", "--gbuffer", "the scene's \"gbuffer\" entry"
  std::filesystem::path path;  // the file itself (a frame pattern's file of one frame)
  bool output = false;
  std::string pattern{};  // the option's frame pattern ("shot.####.exr") when `path` is one of its files
};

// Throws std::invalid_argument naming both options for the first output that is the same file as
// an input or another output: the same path once resolved (absolute, symbolic links followed, "."
// and ".." removed) or, for files that exist, the same device and inode (hard links, bind mounts).
// Entries of one option naming one file (a frame listed twice) are not a conflict.
void refuse_shared_files(const std::vector<NamedFile>& files);

}  // namespace phongcl
