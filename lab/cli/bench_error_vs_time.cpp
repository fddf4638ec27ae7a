// phongcl bench: every precision variant, specialised and general, timed and checked against the
// double-precision scalar reference; the report room writes the table, JSON and chart.
#include <iostream>
#include <stdexcept>

#include "cl/compute_context.h"
#include "cli/bench_arguments.h"
#include "cli/format.h"
#include "reference/reference.h"
#include "report/error_vs_time_report.h"
#include "report/markdown_table.h"
#include "report/report_files.h"
#include "report/statistics.h"
#include "shading/phong_shader.h"

namespace phongcl::cli {

namespace {

// Relative error is |test - expected| / max(|expected|, floor): channels darker than this are
// judged by absolute error instead, so a near-black pixel cannot dominate the maximum.
constexpr double kRelativeErrorFloor = 1e-6;

std::vector<bool> shaded_mask(const GBuffer& gbuffer) {
  std::vector<bool> mask(gbuffer.pixel_count());
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = classify_pixel(gbuffer, i) == PixelClass::shaded;
  return mask;
}

std::vector<ShadeOptions> variants_for(const DeviceInfo& device, std::vector<std::string>& notes) {
  std::vector<ShadeOptions> variants;
  for (Precision precision : all_precisions()) {
    if (precision == Precision::double_precision && !device.has_fp64) {
      notes.push_back("double skipped: the device has no cl_khr_fp64");
      continue;
    }
    for (bool specialise : {true, false}) variants.push_back({precision, specialise});
  }
  return variants;
}

void print_summary(const ErrorVsTimeReport& report, const std::string& written) {
  const std::vector<VariantMeasurement> variants = sorted_by_kernel_time(report.variants);
  const std::vector<bool> front = pareto_front(variants);
  MarkdownTable table;
  table.headers = {"variant", "median kernel", "min kernel", "median end to end", "max rel error", "PSNR", "front"};
  table.align = {ColumnAlign::left, ColumnAlign::right, ColumnAlign::right, ColumnAlign::right,
                 ColumnAlign::right, ColumnAlign::right, ColumnAlign::left};
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const VariantMeasurement& v = variants[i];
    char error[32], psnr[32];
    std::snprintf(error, sizeof error, "%.2e", v.error.max_rel);
    std::snprintf(psnr, sizeof psnr, "%.1f dB", v.error.psnr_db);
    table.rows.push_back({v.label(), milliseconds(v.kernel_median_ms), milliseconds(v.kernel_min_ms),
                          milliseconds(v.end_to_end_median_ms), error, psnr, front[i] ? "yes" : ""});
  }
  std::cout << "  runs       " << report.runs << " timed per variant after one warm-up; median and min; kernel time "
            << "from profiling events, end to end = pack + upload + kernel + download; builds excluded\n"
            << "  error      against the double reference on " << with_commas(report.shaded_pixels)
            << " shaded pixels; relative error floor " << kRelativeErrorFloor << "\n";
  for (const auto& note : report.notes) std::cout << "  note       " << note << "\n";
  std::cout << "\n" << table.render() << "\n  wrote      " << written << "\n";
}

}  // namespace

void run_error_vs_time_bench(const BenchArguments& args) {
  if (args.report_dir.empty()) throw std::invalid_argument("bench: --report DIR is required");
  create_report_directory(args.report_dir);  // fail now, not after minutes of measuring
  const Scene scene = args.inputs.load_scene();
  const GBuffer gbuffer = args.inputs.load_gbuffer(scene);
  ProgramCache cache(ProgramCache::default_directory());
  PhongShader shader(make_compute_context(pick_device(args.device)), cache);
  const DeviceInfo& device = shader.compute().device.info;

  ErrorVsTimeReport report;
  report.scene_file = scene.source.string();
  report.gbuffer_file = gbuffer.source.string();
  report.device = describe(device);
  report.width = gbuffer.width;
  report.height = gbuffer.height;
  report.runs = args.runs;
  report.relative_error_floor = kRelativeErrorFloor;
  for (const Light& light : scene.lights) ++(light.type == LightType::point ? report.point_lights : report.directional_lights);
  const std::vector<ShadeOptions> options = variants_for(device, report.notes);

  std::cout << "phongcl bench: " << report.scene_file << " + " << report.gbuffer_file << "\n"
            << "  image      " << gbuffer.width << " x " << gbuffer.height << ", " << report.point_lights << " point + "
            << report.directional_lights << " directional lights\n"
            << "  device     " << report.device << "\n"
            << "  reference  computing (double, scalar, once for every variant)..." << std::flush;
  const Image reference = reference_image(scene, gbuffer);
  const std::vector<bool> mask = shaded_mask(gbuffer);
  for (bool shaded : mask) report.shaded_pixels += shaded ? 1 : 0;
  std::cout << " done\n  variants   " << options.size() << ": warm-up and error..." << std::flush;

  // The warm-up builds (or loads) each program and is not timed. Its image is the one the error
  // is measured on: later runs use the same program on the same input and shade the same image.
  for (const ShadeOptions& option : options) {
    const ShadeResult warm_up = shader.shade(scene, gbuffer, option);
    VariantMeasurement& m = report.variants.emplace_back();
    m.precision = to_string(option.precision);
    m.specialised = option.specialise;
    m.build_options = warm_up.build_options;
    m.error = compare_images(warm_up.image, reference, kRelativeErrorFloor, mask);
  }
  // Timed runs round-robin over the variants, so drifting background load on a shared machine
  // falls on every variant alike instead of on whichever ran during it.
  std::cout << " timing..." << std::flush;
  for (int run = 0; run < args.runs; ++run) {
    for (std::size_t v = 0; v < options.size(); ++v) {
      const ShadeTimings timings = shader.shade(scene, gbuffer, options[v]).timings;
      report.variants[v].kernel_ms.push_back(timings.kernel_ms);
      report.variants[v].end_to_end_ms.push_back(timings.total_ms);
    }
  }
  for (VariantMeasurement& m : report.variants) {
    m.kernel_median_ms = median(m.kernel_ms);
    m.kernel_min_ms = minimum(m.kernel_ms);
    m.end_to_end_median_ms = median(m.end_to_end_ms);
  }
  std::cout << " done\n";

  write_error_vs_time_report(report, args.report_dir);
  print_summary(report, args.report_dir + "/{report.md, report.json, error_vs_time.svg}");
}

}  // namespace phongcl::cli
