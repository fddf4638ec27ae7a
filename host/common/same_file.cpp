#include "common/same_file.h"

#include <sys/stat.h>

#include <map>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace phongcl {

namespace fs = std::filesystem;

namespace {

fs::path resolved(const fs::path& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (ec) return path.lexically_normal();
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

std::string described(const NamedFile& file) {
  if (file.pattern.empty()) return file.option + " '" + file.path.string() + "'";
  return file.option + " '" + file.pattern + "' (" + file.path.string() + ")";
}

bool same_option(const NamedFile& a, const NamedFile& b) { return a.option == b.option && a.output == b.output; }

}  // namespace

void refuse_shared_files(const std::vector<NamedFile>& files) {
  // The first entry seen of each file; an output meeting anything already there is refused.
  std::map<std::string, const NamedFile*> by_path;
  std::map<std::pair<dev_t, ino_t>, const NamedFile*> by_inode;
  const auto check = [](const NamedFile& earlier, const NamedFile& file) {
    if (!(earlier.output || file.output) || same_option(earlier, file)) return;
    const NamedFile& output = file.output ? file : earlier;
    const NamedFile& other = file.output ? earlier : file;
    throw std::invalid_argument(described(output) + " and " + described(other) + " are the same file: " +
                                (other.output ? "two outputs cannot share a file"
                                              : "an output cannot replace an input"));
  };
  for (const NamedFile& file : files) {
    const auto [at_path, new_path] = by_path.try_emplace(resolved(file.path).native(), &file);
    if (!new_path) check(*at_path->second, file);
    struct stat status {};
    if (::stat(file.path.c_str(), &status) != 0) continue;
    const auto [at_inode, new_inode] = by_inode.try_emplace({status.st_dev, status.st_ino}, &file);
    if (!new_inode) check(*at_inode->second, file);
  }
}

}  // namespace phongcl
