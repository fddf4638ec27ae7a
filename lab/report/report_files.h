#pragma once
// Report output: a directory made up front (so a bad path fails before a long benchmark, not
// after it) and text files (Markdown, JSON, SVG) written whole or not at all.
#include <filesystem>
#include <string>

namespace phongcl {

// Creates `directory` and its parents if needed. Throws std::runtime_error naming it when it
// cannot be created or is not a directory.
void create_report_directory(const std::filesystem::path& directory);

// Writes `text` to a temporary next to `file`, then renames it over `file`. Throws InputError
// naming the file when it cannot be written.
void write_text_file(const std::filesystem::path& file, const std::string& text);

}  // namespace phongcl
