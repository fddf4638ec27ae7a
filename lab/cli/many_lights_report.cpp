#include "cli/many_lights_report.h"

#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "report/markdown_table.h"
#include "report/report_files.h"
#include "report/svg_chart.h"

namespace phongcl::cli {

namespace {

std::string cell(const char* pattern, double value) { return format_cell(pattern, value); }

}  // namespace

std::string many_lights_table(const std::vector<ManyLightsResult>& results) {
  MarkdownTable table;
  table.headers = {"impl", "lights", "median ms", "min ms", "max ms", "runs", "culling ms", "lights/tile", "holding/tile",
                   "lights/pixel shaded", "lights/pixel reached", "lights/pixel tile reached", "effective Mpix-lights/s",
                   "max rel err"};
  table.align = {ColumnAlign::left};
  table.align.resize(table.headers.size(), ColumnAlign::right);
  for (const ManyLightsResult& r : results) {
    table.rows.push_back({r.impl, std::to_string(r.lights), cell("%.2f", r.time.median_ms), cell("%.2f", r.time.min_ms),
                          cell("%.2f", r.time.max_ms), std::to_string(r.time.runs) + (r.single_run ? " (>10 s)" : ""),
                          r.culling_ms ? cell("%.2f", *r.culling_ms) : "", r.mean_lights_per_tile > 0 ? cell("%.1f", r.mean_lights_per_tile) : "",
                          r.mean_lights_per_tile > 0 ? cell("%.1f", r.mean_holding_per_tile) : "",
                          cell("%.1f", r.mean_lights_per_pixel), cell("%.1f", r.mean_lights_reaching),
                          r.mean_lights_reaching_tile > 0 ? cell("%.1f", r.mean_lights_reaching_tile) : "",
                          cell("%.0f", r.effective_mpix_lights_per_s), r.max_rel_err ? cell("%.2e", *r.max_rel_err) : "n/a"});
  }
  return table.render();
}

std::string many_lights_json(const ManyLightsMachine& machine, const std::vector<ManyLightsResult>& results) {
  nlohmann::json json;
  json["machine"] = {{"cpu", machine.cpu},       {"cores", machine.cores},   {"device", machine.device},
                     {"loadavg", machine.loadavg}, {"width", machine.width}, {"height", machine.height},
                     {"tile_size", machine.tile_size}, {"list_rows", machine.list_rows}};
  json["results"] = nlohmann::json::array();
  for (const ManyLightsResult& r : results) {
    json["results"].push_back({{"impl", r.impl},
                               {"lights", r.lights},
                               {"median_ms", r.time.median_ms},
                               {"min_ms", r.time.min_ms},
                               {"max_ms", r.time.max_ms},
                               {"runs", r.time.runs},
                               {"culling_ms", r.culling_ms ? nlohmann::json(*r.culling_ms) : nlohmann::json(nullptr)},
                               {"mean_lights_per_pixel", r.mean_lights_per_pixel},
                               {"mean_lights_reaching", r.mean_lights_reaching},
                               {"mean_lights_reaching_tile", r.mean_lights_reaching_tile},
                               {"mean_lights_per_tile", r.mean_lights_per_tile},
                               {"mean_holding_per_tile", r.mean_holding_per_tile},
                               {"effective_mpix_lights_per_s", r.effective_mpix_lights_per_s},
                               {"max_rel_err", r.max_rel_err ? nlohmann::json(*r.max_rel_err) : nlohmann::json(nullptr)},
                               {"schedule", r.schedule.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.schedule)}});
  }
  return json.dump(2) + "\n";
}

void write_many_lights_report(const std::string& directory, const ManyLightsMachine& machine,
                              const std::vector<ManyLightsResult>& results) {
  const std::filesystem::path dir(directory);
  create_report_directory(dir);
  Chart chart;
  chart.title = "Frame time against light count, " + std::to_string(machine.width) + "x" + std::to_string(machine.height);
  chart.x = {"lights", true};
  chart.y = {"ms per frame (median)", true};
  std::map<std::string, ChartSeries> series;
  for (const ManyLightsResult& r : results) {
    ChartSeries& s = series[r.impl];
    s.name = r.impl;
    s.line = true;
    s.points.push_back({static_cast<double>(r.lights), std::max(r.time.median_ms, 1e-3), ""});
  }
  for (auto& [name, s] : series) chart.series.push_back(s);
  write_text_file(dir / "frame_ms_vs_lights.svg", render_svg(chart));
  write_text_file(dir / "results.json", many_lights_json(machine, results));
  std::string md = "# Many lights: tiled culling against the unculled kernel and a C++ peer\n\n";
  md += "Inputs: " + machine.inputs + ", " + std::to_string(machine.width) + "x" + std::to_string(machine.height) +
        ", tiles " + std::to_string(machine.tile_size) + "x" + std::to_string(machine.tile_size) +
        ", a light list per " + std::to_string(machine.tile_size) + "x" + std::to_string(machine.list_rows) +
        " pixels.\n\n";
  md += "- CPU: " + machine.cpu + ", " + std::to_string(machine.cores) + " cores; device: " + machine.device + "\n";
  md += "- Load average at the start: " + machine.loadavg + "\n\n";
  md += "Lights: point and spot alternately, quadratic falloff, one range for all, spread through the box of the "
        "shaded positions (`lab/peers/many_lights.h`). Times: median of the timed runs after one untimed warm-up; "
        "OpenCL from profiling events (culling passes included, and shown apart), cpp-tiled wall clock "
        "(cpp-tiled-best: the fastest of its schedules, with --peer-schedules). "
        "Effective Mpix-lights/s counts only the pixel-light pairs shaded: those the culling keeps, or every light "
        "for the unculled kernel. Lights reached: per shaded pixel, the lights that reach it, and the lights that reach "
        "a shaded pixel of its list's pixels (what one list per tile must keep at the least). Errors against the "
        "double reference on a sample of rows.\n\n";
  md += many_lights_table(results) + "\n";
  for (const ManyLightsResult& r : results)
    if (!r.schedule.empty()) md += "- " + r.impl + " at " + std::to_string(r.lights) + " lights: " + r.schedule + "\n";
  md += "\n![frame time](frame_ms_vs_lights.svg)\n";
  write_text_file(dir / "report.md", md);
}

}  // namespace phongcl::cli
