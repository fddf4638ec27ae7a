#include "cli/throughput_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "report/markdown_table.h"
#include "report/report_files.h"
#include "report/svg_chart.h"

namespace phongcl::cli {

namespace {

std::string fixed(double value, int decimals) {
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string significant(double value) {
  char text[48];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

std::string size_of(const ThroughputResult& r) { return std::to_string(r.width) + "x" + std::to_string(r.height); }

// The scalar peer's time for the same case, which every speed-up is quoted against.
std::map<std::string, double> scalar_medians(const std::vector<ThroughputResult>& results) {
  std::map<std::string, double> medians;
  for (const auto& r : results) {
    if (r.impl == "cpp-scalar") medians[size_of(r) + "/" + std::to_string(r.lights)] = r.time.median_ms;
  }
  return medians;
}

}  // namespace

RunStats summarize(std::vector<double> milliseconds) {
  RunStats stats;
  if (milliseconds.empty()) return stats;
  std::sort(milliseconds.begin(), milliseconds.end());
  const std::size_t n = milliseconds.size();
  stats.median_ms = n % 2 ? milliseconds[n / 2] : 0.5 * (milliseconds[n / 2 - 1] + milliseconds[n / 2]);
  stats.min_ms = milliseconds.front();
  stats.max_ms = milliseconds.back();
  stats.runs = static_cast<int>(n);
  return stats;
}

std::string markdown_table(const std::vector<ThroughputResult>& results) {
  MarkdownTable table;
  table.headers = {"size", "lights", "impl", "variant", "runs", "median ms", "min-max ms", "Mpix/s", "Mpix-lights/s",
                   "B/px", "flop/px", "roofline Mpix/s", "of roofline", "x scalar", "max rel err", "end-to-end ms"};
  table.align = {ColumnAlign::left,  ColumnAlign::right, ColumnAlign::left,  ColumnAlign::left,
                 ColumnAlign::right, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right,
                 ColumnAlign::right, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right,
                 ColumnAlign::right, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right};
  const auto scalar = scalar_medians(results);
  for (const auto& r : results) {
    if (!r.not_run.empty()) {
      std::vector<std::string> row{size_of(r), std::to_string(r.lights), r.impl, r.variant, r.not_run};
      row.resize(table.headers.size());
      table.rows.push_back(row);
      continue;
    }
    const auto base = scalar.find(size_of(r) + "/" + std::to_string(r.lights));
    std::string runs = std::to_string(r.time.runs);
    if (r.timed_row_step > 1) runs += " (rows 1/" + std::to_string(r.timed_row_step) + ")";
    std::string error = r.max_rel_err ? significant(*r.max_rel_err) : "n/a";
    if (r.max_rel_err && r.error_row_step > 1) error += " (rows 1/" + std::to_string(r.error_row_step) + ")";
    table.rows.push_back({size_of(r), std::to_string(r.lights), r.impl, r.variant, runs, fixed(r.time.median_ms, 2),
                          fixed(r.time.min_ms, 2) + "-" + fixed(r.time.max_ms, 2), fixed(r.mpix_per_s, 1),
                          fixed(r.mpix_lights_per_s, 1), fixed(r.bytes_per_pixel, 0), fixed(r.flops_per_pixel, 0),
                          fixed(r.roofline_mpix_per_s, 1), fixed(100.0 * r.roofline_fraction, 1) + "%",
                          base == scalar.end() ? "" : fixed(base->second / r.time.median_ms, 1),
                          error, r.end_to_end ? fixed(r.end_to_end->median_ms, 2) : ""});
  }
  return table.render();
}

std::string halide_note(const std::vector<ThroughputResult>& results) {
  std::string schedules, compile_times;
  for (const auto& r : results) {
    if (r.impl != "halide" || !r.compile_ms) continue;
    if (schedules.find(r.schedule) == std::string::npos) schedules += (schedules.empty() ? "" : ", ") + r.schedule;
    compile_times += (compile_times.empty() ? "" : ", ") + fixed(*r.compile_ms, 0) + " (" + size_of(r) + ", " +
                     std::to_string(r.lights) + ")";
  }
  if (schedules.empty()) return "";
  return "halide: schedule " + schedules + "; JIT compile ms, not in the times: " + compile_times + "\n";
}

std::string results_json(const MachineLimits& machine, const std::vector<ThroughputResult>& results, const std::string& load) {
  nlohmann::ordered_json json;
  json["machine"] = {{"bandwidth_gbs", machine.bandwidth_gbs},
                     {"fma_gflops", machine.fma_gflops},
                     {"cores", machine.cores},
                     {"cpu", machine.cpu},
                     {"load", load}};
  json["results"] = nlohmann::ordered_json::array();
  for (const auto& r : results) {
    if (!r.not_run.empty()) {
      json["results"].push_back({{"impl", r.impl}, {"variant", r.variant}, {"lights", r.lights}, {"width", r.width},
                                 {"height", r.height}, {"not_run", r.not_run}, {"median_ms", nullptr}, {"min_ms", nullptr},
                                 {"max_ms", nullptr}, {"max_rel_err", nullptr}});
      continue;
    }
    nlohmann::ordered_json entry = {{"impl", r.impl},
                                    {"variant", r.variant},
                                    {"lights", r.lights},
                                    {"width", r.width},
                                    {"height", r.height},
                                    {"median_ms", r.time.median_ms},
                                    {"min_ms", r.time.min_ms},
                                    {"max_ms", r.time.max_ms},
                                    {"mpix_per_s", r.mpix_per_s},
                                    {"mpix_lights_per_s", r.mpix_lights_per_s},
                                    {"roofline_fraction", r.roofline_fraction},
                                    {"max_rel_err", r.max_rel_err ? nlohmann::ordered_json(*r.max_rel_err) : nullptr}};
    if (r.end_to_end) entry["end_to_end_median_ms"] = r.end_to_end->median_ms;
    entry["runs"] = r.time.runs;
    entry["timed_row_step"] = r.timed_row_step;
    entry["error_row_step"] = r.error_row_step;
    entry["bytes_per_pixel"] = r.bytes_per_pixel;
    entry["flops_per_pixel"] = r.flops_per_pixel;
    if (!r.schedule.empty()) entry["schedule"] = r.schedule;
    if (r.compile_ms) entry["compile_ms"] = *r.compile_ms;
    json["results"].push_back(entry);
  }
  return json.dump(2) + "\n";
}

void write_throughput_report(const std::string& directory, const MachineLimits& machine, const std::string& device,
                             const std::string& inputs, const std::string& load, const std::vector<ThroughputResult>& results) {
  const std::filesystem::path dir(directory);
  std::filesystem::create_directories(dir);

  // Mpixel-lights/s against lights at the light sweep's size (the first result's); log axes, so lights >= 1.
  Chart chart;
  chart.title = "Throughput against lights";
  chart.x = {"lights", true};
  chart.y = {"Mpixel-lights/s", true};
  std::map<std::string, std::size_t> series_of;
  const std::string sweep_size = results.empty() ? "" : size_of(results.front());
  for (const auto& r : results) {
    if (r.lights < 1 || size_of(r) != sweep_size || !r.not_run.empty()) continue;
    const std::string name = r.impl + (r.impl == "opencl" ? " " + r.variant : "");
    auto [it, inserted] = series_of.emplace(name, chart.series.size());
    if (inserted) chart.series.push_back({name, {}, MarkerShape::circle, true, ""});
    chart.series[it->second].points.push_back({static_cast<double>(r.lights), r.mpix_lights_per_s, ""});
  }
  chart.title += " (" + sweep_size + ")";
  if (!chart.series.empty()) write_text_file(dir / "mpix_lights_vs_lights.svg", render_svg(chart));

  std::string md = "# Throughput: OpenCL kernel against C++ peers\n\n";
  md += "Measured with `phongcl bench --throughput` on " + inputs + ".\n\n";
  md += "## Machine\n\n- CPU: " + machine.cpu + ", " + std::to_string(machine.cores) + " cores (OpenMP threads)\n";
  md += "- OpenCL device: " + device + "\n";
  md += "- Load: " + load + " (1, 5 and 15 minute averages)\n";
  md += "- Memory bandwidth: " + fixed(machine.bandwidth_gbs, 1) +
        " GB/s (STREAM-style float triad a = b + s c, 3 x 256 MB, all cores, best of 5; 12 bytes per element)\n";
  md += "- FMA peak: " + fixed(machine.fma_gflops, 1) +
        " GFLOP/s single precision (16 independent 512-bit FMA chains per core, all cores; 2 flops per lane)\n\n";
  md += "## Method\n\n"
        "- One untimed warm-up (it includes the OpenCL kernel build), then timed runs; median, min and max.\n"
        "- opencl: kernel time from profiling events; end-to-end is the wall clock of pack + upload + kernel +\n"
        "  download (PhongShader::shade, build excluded). Peers: wall clock of the shading loop on input packed\n"
        "  once beforehand (structure of arrays, positions relative to the eye); packing is not timed.\n"
        "- halide: the same formula as a JIT-compiled Halide pipeline (lab/peers/halide_peer), in its own process\n"
        "  on the same packed input; wall clock of realize(); the JIT compile is reported below, not timed.\n"
        "- Runs: the requested count, fewer (at least 3) where that would exceed about 5 s per measurement.\n"
        "  cpp-scalar on large cases is timed on every n-th row (\"rows 1/n\"), its times scaled to the whole frame.\n"
        "- Lights: the scene's lights replaced by N generated ones (half point, half directional, deterministic).\n"
        "  Sizes other than the G-buffer's own are a nearest-neighbour resample of it.\n"
        "- Roofline bound = min(bandwidth / bytes per pixel, FMA peak / flops per pixel); bytes are compulsory\n"
        "  traffic (the inputs the formula needs read once: P and N only with lights; RGBA float written once),\n"
        "  flops the formula's work counted on the peers'\n"
        "  code (lab/peers/work_model.h), the same for every implementation; the double variant's peak is half.\n"
        "- max rel err: against the double-precision reference on shaded pixels (1e-6 absolute floor), over every\n"
        "  n-th row where the reference would be too slow on the whole frame (\"rows 1/n\").\n\n";
  md += "## Results\n\n" + markdown_table(results) + "\n" + halide_note(results) + "\n";
  if (!chart.series.empty()) md += "![Mpixel-lights/s against lights](mpix_lights_vs_lights.svg)\n";
  write_text_file(dir / "report.md", md);
  write_text_file(dir / "results.json", results_json(machine, results, load));
}

}  // namespace phongcl::cli
