#include "cli/shadow_bench_report.h"

#include <limits>

#include <nlohmann/json.hpp>

#include "report/markdown_table.h"
#include "report/pareto.h"
#include "report/report_files.h"
#include "report/svg_chart.h"

namespace phongcl::cli {

namespace {

using nlohmann::json;

// The Pareto front of time and mismatch over every variant, or over the screen-space marches alone
// (exact geometry shadows dominate every march where the scene has geometry; the front among the
// marches is what a G-buffer without geometry chooses from).
std::vector<bool> front_of(const ShadowSceneResult& scene, bool screen_only = false) {
  std::vector<CostPoint> points;
  for (const ShadowVariant& v : scene.variants) {
    const bool counted = !screen_only || v.mode == "screen";
    points.push_back({counted ? v.kernel_ms : std::numeric_limits<double>::infinity(), v.mismatch});
  }
  return pareto_front(points);
}

json scene_json(const ShadowSceneResult& scene) {
  json variants = json::array();
  const std::vector<bool> front = front_of(scene), screen_front = front_of(scene, true);
  for (std::size_t i = 0; i < scene.variants.size(); ++i) {
    const ShadowVariant& v = scene.variants[i];
    variants.push_back({{"label", v.label}, {"mode", v.mode}, {"steps", v.steps}, {"thickness", v.thickness},
                        {"kernel_median_ms", v.kernel_ms}, {"mismatch_fraction", v.mismatch},
                        {"mean_abs_error", v.mean_abs_error}, {"pareto_front", static_cast<bool>(front[i])},
                        {"screen_pareto_front", static_cast<bool>(screen_front[i])}});
  }
  json culling = json::array();
  for (const ShadowCullingVariant& c : scene.culling)
    culling.push_back({{"tile", c.tile}, {"total_median_ms", c.total_ms}, {"culling_median_ms", c.culling_ms},
                       {"candidates_per_pair", c.candidates_per_pair}, {"traversing_pairs", c.traversing_pairs},
                       {"pixels_differing", c.differing}});
  return {{"scene", scene.name}, {"width", scene.width},     {"height", scene.height},
          {"lights", scene.lights}, {"shaded_pixels", scene.shaded}, {"geometry", scene.geometry},
          {"variants", variants}, {"shadow_culling", culling}};
}

json tracers_json(const std::vector<ShadowTracerResult>& results) {
  json tracers = json::array();
  for (const ShadowTracerResult& t : results)
    tracers.push_back({{"name", t.name}, {"bvh_build_ms", t.build_ms}, {"trace_median_ms", t.trace_ms},
                       {"mrays_per_s", t.mrays_per_s}, {"disagreement", t.disagreement}});
  return tracers;
}

json rays_json(const ShadowRaysResult& rays) {
  return {{"device", rays.device}, {"embree", rays.embree}, {"triangles", rays.triangles}, {"rays", rays.rays},
          {"bvh_depth", rays.bvh_depth}, {"mesh_read_ms", rays.mesh_read_ms}, {"bvh_build_ms", rays.bvh_build_ms},
          {"tracers", tracers_json(rays.tracers)}, {"soft_rays", rays.soft_rays},
          {"soft_tracers", tracers_json(rays.soft_tracers)}};
}

// Screen-space variants as one line per thickness (steps in order); geometry and off as markers.
Chart scene_chart(const ShadowSceneResult& scene) {
  Chart chart;
  chart.title = "Shadows, error against run time: " + scene.name + ", " + std::to_string(scene.width) + " x " +
                std::to_string(scene.height);
  chart.x = {"median kernel time (ms, profiling events)", false};
  chart.y = {"pixels whose shadows differ from exact geometry (%)", false};
  std::vector<ChartSeries> screens;
  ChartSeries exact{"geometry (exact) and off", {}, MarkerShape::square, false, "#222222"};
  for (const ShadowVariant& v : scene.variants) {
    if (v.mode != "screen") {
      exact.points.push_back({v.kernel_ms, 100.0 * v.mismatch, v.mode});
      continue;
    }
    auto series = std::find_if(screens.begin(), screens.end(), [&](const ChartSeries& s) {
      return s.name == "screen, thickness " + v.thickness;
    });
    if (series == screens.end()) {
      screens.push_back({"screen, thickness " + v.thickness, {}, MarkerShape::circle, true, ""});
      series = screens.end() - 1;
    }
    series->points.push_back({v.kernel_ms, 100.0 * v.mismatch, std::to_string(v.steps)});
  }
  chart.series = screens;
  chart.series.push_back(exact);
  return chart;
}

}  // namespace

std::string shadow_rays_table(const std::vector<ShadowTracerResult>& tracers) {
  MarkdownTable table{{"tracer", "BVH build ms", "trace ms", "Mrays/s", "opencl / this", "decisions differing"},
                      {},
                      {ColumnAlign::left, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right,
                       ColumnAlign::right, ColumnAlign::right}};
  const double ours = tracers.empty() ? 0.0 : tracers.front().mrays_per_s;
  for (const ShadowTracerResult& tracer : tracers)
    table.rows.push_back({tracer.name, format_cell("%.1f", tracer.build_ms), format_cell("%.2f", tracer.trace_ms),
                          format_cell("%.1f", tracer.mrays_per_s), format_cell("%.2fx", ours / tracer.mrays_per_s),
                          format_cell("%.1e", tracer.disagreement)});
  return table.render();
}

std::string shadow_error_table(const ShadowSceneResult& scene) {
  MarkdownTable table{{"shadows", "median kernel ms", "x unshadowed", "pixels differing", "mean abs error", "front",
                       "screen front"},
                      {},
                      {ColumnAlign::left, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right,
                       ColumnAlign::right, ColumnAlign::left, ColumnAlign::left}};
  const std::vector<bool> front = front_of(scene), screen_front = front_of(scene, true);
  double unshadowed = 0.0;
  for (const ShadowVariant& v : scene.variants)
    if (v.mode == "off") unshadowed = v.kernel_ms;
  for (std::size_t i = 0; i < scene.variants.size(); ++i) {
    const ShadowVariant& v = scene.variants[i];
    table.rows.push_back({v.label, format_cell("%.2f", v.kernel_ms), format_cell("%.2fx", v.kernel_ms / unshadowed),
                          format_cell("%.2f%%", 100.0 * v.mismatch), format_cell("%.2e", v.mean_abs_error),
                          front[i] ? "yes" : "", screen_front[i] ? "yes" : ""});
  }
  return table.render();
}

std::string shadow_culling_table(const ShadowSceneResult& scene) {
  MarkdownTable table{{"shadow rays", "median ms", "culling ms", "x traversal", "candidates per list",
                       "(tile, light) traversing", "pixels differing"},
                      {},
                      {ColumnAlign::left, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right,
                       ColumnAlign::right, ColumnAlign::right, ColumnAlign::right}};
  const double traversal = scene.culling.empty() ? 0.0 : scene.culling.front().total_ms;
  for (const ShadowCullingVariant& c : scene.culling)
    table.rows.push_back({c.tile == 0 ? "every ray traverses the BVH" : "tiled culling, " + std::to_string(c.tile) + "x" +
                                                                          std::to_string(c.tile) + " tiles",
                          format_cell("%.2f", c.total_ms), c.tile == 0 ? "" : format_cell("%.2f", c.culling_ms),
                          format_cell("%.2fx", c.total_ms / traversal),
                          c.tile == 0 ? "" : format_cell("%.1f", c.candidates_per_pair),
                          c.tile == 0 ? "" : format_cell("%.1f%%", 100.0 * c.traversing_pairs),
                          std::to_string(c.differing)});
  return table.render();
}

std::string write_shadow_report(const std::filesystem::path& directory, const ShadowBenchMachine& machine,
                                const std::vector<ShadowSceneResult>& scenes, const ShadowRaysResult& rays) {
  std::string markdown = "# Shadows: error against run time, and shadow rays against Embree\n\n"
                         "Written by `phongcl bench --shadows --report DIR` (docs/shadows.md).\n\n"
                         "- CPU: " + machine.cpu + "; device: " + rays.device + "\n"
                         "- Load average at the start: " + machine.load_start + "; at the end: " + machine.load_end +
                         "\n\nEvery light casts shadows; exact geometry shadows are the reference. A pixel's shadows "
                         "differ when the images differ there by more than 1% of its unshadowed value. \"front\": "
                         "on the Pareto front of time and pixels differing among every variant; \"screen front\": "
                         "among the screen-space marches alone (what a G-buffer without geometry chooses from).\n";
  json document = {{"machine", {{"cpu", machine.cpu}, {"loadavg_start", machine.load_start},
                                {"loadavg_end", machine.load_end}}},
                   {"scenes", json::array()},
                   {"rays", rays_json(rays)}};
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const std::string chart = "error_" + std::to_string(k) + ".svg";
    write_text_file(directory / chart, render_svg(scene_chart(scenes[k])));
    markdown += "\n## " + scenes[k].name + ", " + std::to_string(scenes[k].width) + " x " +
                std::to_string(scenes[k].height) + "\n\nExact shadows: " + scenes[k].geometry + ".\n\n" +
                shadow_error_table(scenes[k]) + "\n![" + scenes[k].name + "](" + chart + ")\n\n"
                "Tiled shadow culling against the traversal: every light's shadow rays per pixel without the "
                "shading around them (the lab's `count_blocked_lights`), the culling passes included.\n\n" +
                shadow_culling_table(scenes[k]);
    document["scenes"].push_back(scene_json(scenes[k]));
  }
  markdown += "\n## Shadow rays: OpenCL against Embree\n\n" + std::to_string(rays.rays) + " rays on " +
              std::to_string(rays.triangles) + " triangles (BVH depth " + std::to_string(rays.bvh_depth) + "); " +
              rays.embree + ".\n\n" + shadow_rays_table(rays.tracers) + "\nThe same lights' soft shadow rays (spheres, 16 per pixel): " +
              std::to_string(rays.soft_rays) + " rays.\n\n" + shadow_rays_table(rays.soft_tracers);
  write_text_file(directory / "report.md", markdown);
  write_text_file(directory / "report.json", document.dump(2) + "\n");
  return (directory / "{report.md, report.json, error_*.svg}").string();
}

}  // namespace phongcl::cli
