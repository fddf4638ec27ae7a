#include "report/markdown_table.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace phongcl {

namespace {

std::string escape_cell(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    if (c == '|') escaped += "\\|";
    else if (c == '\n' || c == '\r') escaped += ' ';
    else escaped += c;
  }
  return escaped;
}

// Display width: UTF-8 continuation bytes take no column (headers may hold "µs" or "±").
std::size_t display_width(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

std::string pad(const std::string& text, std::size_t width, ColumnAlign align) {
  const std::string fill(width - std::min(width, display_width(text)), ' ');
  return align == ColumnAlign::right ? fill + text : text + fill;
}

}  // namespace

std::string MarkdownTable::render() const {
  std::vector<std::vector<std::string>> cells;
  cells.reserve(rows.size() + 1);
  cells.push_back({});
  for (const auto& header : headers) cells.back().push_back(escape_cell(header));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (rows[r].size() != headers.size())
      throw std::invalid_argument("MarkdownTable: row " + std::to_string(r) + " has " + std::to_string(rows[r].size()) +
                                  " cells for " + std::to_string(headers.size()) + " columns");
    cells.push_back({});
    for (const auto& cell : rows[r]) cells.back().push_back(escape_cell(cell));
  }

  const std::size_t columns = headers.size();
  std::vector<std::size_t> widths(columns, 3);  // "---" is the shortest separator
  for (const auto& line : cells)
    for (std::size_t c = 0; c < columns; ++c) widths[c] = std::max(widths[c], display_width(line[c]));
  auto align_of = [&](std::size_t c) { return c < align.size() ? align[c] : ColumnAlign::left; };

  std::string text;
  auto append_line = [&](const std::vector<std::string>& line) {
    text += '|';
    for (std::size_t c = 0; c < columns; ++c) text += ' ' + pad(line[c], widths[c], align_of(c)) + " |";
    text += '\n';
  };
  append_line(cells.front());
  text += '|';
  for (std::size_t c = 0; c < columns; ++c) {
    const bool right = align_of(c) == ColumnAlign::right;
    text += ' ' + std::string(widths[c] - (right ? 1 : 0), '-') + (right ? ":" : "") + " |";
  }
  text += '\n';
  for (std::size_t r = 1; r < cells.size(); ++r) append_line(cells[r]);
  return text;
}

std::string format_cell(const char* pattern, double value) {
  char text[48];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

}  // namespace phongcl
