#pragma once
// A Markdown table: headers, rows of cells, per-column alignment. Columns are padded to a common
// width so the text reads as a table in a terminal too.
#include <string>
#include <vector>

namespace phongcl {

enum class ColumnAlign { left, right };

struct MarkdownTable {
  std::vector<std::string> headers;
  std::vector<std::vector<std::string>> rows;  // each as many cells as headers
  std::vector<ColumnAlign> align;              // per column; missing entries are left

  // Throws std::invalid_argument when a row's cell count differs from the header count.
  // A '|' inside a cell is escaped; newlines become spaces.
  std::string render() const;
};

// One number as table text, with a printf pattern for a double ("%.2e", "%.1f").
std::string format_cell(const char* pattern, double value);

}  // namespace phongcl
