// The three report files, written into one directory.
#include <nlohmann/json.hpp>

#include "report/error_vs_time_report.h"
#include "report/report_files.h"

namespace phongcl {

void write_error_vs_time_report(const ErrorVsTimeReport& report, const std::filesystem::path& directory) {
  create_report_directory(directory);
  write_text_file(directory / "report.md", render_markdown(report));
  write_text_file(directory / "report.json", to_json(report).dump(2) + "\n");
  write_text_file(directory / "error_vs_time.svg", render_svg(error_vs_time_chart(report)));
}

}  // namespace phongcl
