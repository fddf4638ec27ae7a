// report.json: the report's data for tools, in the table's order, with units in the field names.
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "report/error_vs_time_report.h"

namespace phongcl {

namespace {

using nlohmann::json;

// JSON has no infinity: PSNR of identical images is written as null.
json number_or_null(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json error_json(const ErrorStats& e) {
  return {{"pixels_compared", e.pixels_compared},
          {"max_abs", e.max_abs},
          {"max_rel", e.max_rel},
          {"rmse", e.rmse},
          {"psnr_db", number_or_null(e.psnr_db)},
          {"worst", {{"x", e.worst_x}, {"y", e.worst_y}, {"channel", e.worst_channel}, {"pixel_index", e.worst_pixel},
                     {"value", e.worst_test}, {"expected", e.worst_expected}}},
          {"nonfinite_mismatches", e.nonfinite_mismatches}};
}

ErrorStats error_from_json(const json& j) {
  ErrorStats e;
  e.pixels_compared = j.at("pixels_compared").get<std::size_t>();
  e.max_abs = j.at("max_abs").get<double>();
  e.max_rel = j.at("max_rel").get<double>();
  e.rmse = j.at("rmse").get<double>();
  e.psnr_db = j.at("psnr_db").is_null() ? std::numeric_limits<double>::infinity() : j.at("psnr_db").get<double>();
  const json& worst = j.at("worst");
  e.worst_x = worst.at("x").get<int>();
  e.worst_y = worst.at("y").get<int>();
  e.worst_channel = worst.at("channel").get<int>();
  e.worst_pixel = worst.at("pixel_index").get<std::size_t>();
  e.worst_test = worst.at("value").get<double>();
  e.worst_expected = worst.at("expected").get<double>();
  e.nonfinite_mismatches = j.at("nonfinite_mismatches").get<std::size_t>();
  return e;
}

}  // namespace

json to_json(const ErrorVsTimeReport& report) {
  const std::vector<VariantMeasurement> variants = sorted_by_kernel_time(report.variants);
  const std::vector<bool> front = pareto_front(variants);
  json rows = json::array();
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const VariantMeasurement& v = variants[i];
    rows.push_back({{"precision", v.precision},
                    {"kernel", v.kernel_kind()},
                    {"build_options", v.build_options},
                    {"kernel_median_ms", v.kernel_median_ms},
                    {"kernel_min_ms", v.kernel_min_ms},
                    {"end_to_end_median_ms", v.end_to_end_median_ms},
                    {"kernel_ms_runs", v.kernel_ms},
                    {"end_to_end_ms_runs", v.end_to_end_ms},
                    {"error", error_json(v.error)},
                    {"pareto_front", static_cast<bool>(front[i])}});
  }
  return {{"scene", report.scene_file},
          {"gbuffer", report.gbuffer_file},
          {"width", report.width},
          {"height", report.height},
          {"shaded_pixels", report.shaded_pixels},
          {"point_lights", report.point_lights},
          {"directional_lights", report.directional_lights},
          {"device", report.device},
          {"runs", report.runs},
          {"statistic", "median and min over the timed runs, after one untimed warm-up"},
          {"kernel_time", "OpenCL profiling events of the kernel launches; build excluded"},
          {"end_to_end_time", "wall clock of pack + upload + kernel + download; build excluded"},
          {"error", "against the double-precision scalar reference on every shaded pixel, channels R, G, B"},
          {"relative_error_floor", report.relative_error_floor},
          {"notes", report.notes},
          {"variants", rows}};
}

ErrorVsTimeReport error_vs_time_report_from_json(const json& j) {
  ErrorVsTimeReport report;
  report.scene_file = j.at("scene").get<std::string>();
  report.gbuffer_file = j.at("gbuffer").get<std::string>();
  report.width = j.at("width").get<int>();
  report.height = j.at("height").get<int>();
  report.shaded_pixels = j.at("shaded_pixels").get<std::size_t>();
  report.point_lights = j.at("point_lights").get<int>();
  report.directional_lights = j.at("directional_lights").get<int>();
  report.device = j.at("device").get<std::string>();
  report.runs = j.at("runs").get<int>();
  report.relative_error_floor = j.at("relative_error_floor").get<double>();
  report.notes = j.at("notes").get<std::vector<std::string>>();
  for (const json& row : j.at("variants")) {
    VariantMeasurement v;
    v.precision = row.at("precision").get<std::string>();
    v.specialised = row.at("kernel").get<std::string>() == "specialised";
    v.build_options = row.at("build_options").get<std::string>();
    v.kernel_median_ms = row.at("kernel_median_ms").get<double>();
    v.kernel_min_ms = row.at("kernel_min_ms").get<double>();
    v.end_to_end_median_ms = row.at("end_to_end_median_ms").get<double>();
    v.kernel_ms = row.at("kernel_ms_runs").get<std::vector<double>>();
    v.end_to_end_ms = row.at("end_to_end_ms_runs").get<std::vector<double>>();
    v.error = error_from_json(row.at("error"));
    report.variants.push_back(std::move(v));
  }
  return report;
}

}  // namespace phongcl
