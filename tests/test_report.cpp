// The report room: Pareto front, Markdown table, SVG chart, JSON round trip; and `phongcl bench`
// end to end on the default scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

#include "cl/device.h"
#include "cli_runner.h"
#include "opencl_required.h"
#include "report/error_vs_time_report.h"
#include "report/markdown_table.h"
#include "report/pareto.h"
#include "report/statistics.h"
#include "report/svg_chart.h"
#include "temp_dir.h"

namespace phongcl {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

TEST(Pareto, KeepsOnlyPointsNoOtherBeatsInBoth) {
  // (time, error): the third is beaten by the second in both; the fourth is slower but better.
  const std::vector<CostPoint> points = {{1, 1e-2}, {2, 1e-5}, {3, 1e-4}, {4, 1e-7}};
  EXPECT_EQ(pareto_front(points), (std::vector<bool>{true, true, false, true}));
}

TEST(Pareto, TiesInOneCostAreDecidedByTheOther) {
  // Same time, worse error: dominated. Same error, slower: dominated.
  const std::vector<CostPoint> points = {{1, 1e-3}, {1, 1e-2}, {2, 1e-3}};
  EXPECT_EQ(pareto_front(points), (std::vector<bool>{true, false, false}));
}

TEST(Pareto, EqualPointsBothStayOnTheFront) {
  const std::vector<CostPoint> points = {{1, 1e-3}, {1, 1e-3}, {5, 1e-2}};
  EXPECT_EQ(pareto_front(points), (std::vector<bool>{true, true, false}));
}

TEST(Pareto, NonFinitePointsAreNeverOnItAndDominateNothing) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  const std::vector<CostPoint> points = {{0.5, inf}, {0.1, nan}, {2, 1e-3}};
  EXPECT_EQ(pareto_front(points), (std::vector<bool>{false, false, true}));
  EXPECT_TRUE(pareto_front(std::vector<CostPoint>{}).empty());
}

TEST(Statistics, MedianOfOddAndEvenCountsAndMinimum) {
  EXPECT_DOUBLE_EQ(median({3, 1, 2}), 2.0);
  EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(minimum({4, 1, 3}), 1.0);
  EXPECT_THROW(median({}), std::invalid_argument);
}

TEST(MarkdownTable, RendersHeaderSeparatorAlignmentAndEscapes) {
  MarkdownTable table{{"name", "ms"}, {{"a|b", "1.5"}, {"long name", "12.25"}}, {ColumnAlign::left, ColumnAlign::right}};
  const std::string expected =
      "| name      |    ms |\n"
      "| --------- | ----: |\n"
      "| a\\|b      |   1.5 |\n"
      "| long name | 12.25 |\n";
  EXPECT_EQ(table.render(), expected);
}

TEST(MarkdownTable, RejectsARowOfTheWrongWidth) {
  MarkdownTable table{{"a", "b"}, {{"only one"}}, {}};
  EXPECT_THROW(table.render(), std::invalid_argument);
}

// Eight variants like a real bench run: four precisions, specialised and general.
ErrorVsTimeReport sample_report() {
  ErrorVsTimeReport report;
  report.scene_file = "scenes/test/scene.json";
  report.gbuffer_file = "scenes/test/gbuffer.exr";
  report.device = "test device";
  report.width = 64;
  report.height = 32;
  report.shaded_pixels = 2000;
  report.point_lights = 2;
  report.directional_lights = 1;
  report.runs = 3;
  report.notes = {"a note"};
  const std::vector<std::pair<std::string, double>> precisions = {
      {"double", 1e-12}, {"precise", 3e-7}, {"fast", 4e-5}, {"half-storage", 1e-2}};
  double precision_time = 10;  // falls as the error rises; a general kernel is 0.5 ms slower
  for (const auto& [precision, error] : precisions) {
    for (bool specialised : {true, false}) {
      const double time = precision_time + (specialised ? 0.0 : 0.5);
      VariantMeasurement v;
      v.precision = precision;
      v.specialised = specialised;
      v.build_options = "-DTEST";
      v.kernel_ms = {time + 1, time, time + 2};
      v.end_to_end_ms = {2 * time, 2 * time + 1, 2 * time + 2};
      v.kernel_median_ms = time + 1;
      v.kernel_min_ms = time;
      v.end_to_end_median_ms = 2 * time + 1;
      v.error.pixels_compared = 2000;
      v.error.max_abs = error / 2;
      v.error.max_rel = error;
      v.error.rmse = error / 10;
      v.error.psnr_db = 100;
      v.error.worst_pixel = 7 * 64 + 5;
      v.error.worst_x = 5;
      v.error.worst_y = 7;
      v.error.worst_channel = 1;
      v.error.worst_test = 0.5;
      v.error.worst_expected = 0.5 - error / 2;
      report.variants.push_back(v);
    }
    precision_time -= 2;
  }
  report.variants[1].error.psnr_db = std::numeric_limits<double>::infinity();  // identical images
  return report;
}

TEST(ErrorVsTimeReport, FrontFollowsTimeAndError) {
  // Times fall as errors rise, so every specialised kernel (faster than its general twin, same
  // error) is on the front and no general one is.
  const ErrorVsTimeReport report = sample_report();
  const auto variants = sorted_by_kernel_time(report.variants);
  const auto front = pareto_front(variants);
  for (std::size_t i = 0; i < variants.size(); ++i) EXPECT_EQ(front[i], variants[i].specialised) << variants[i].label();
  EXPECT_EQ(variants.front().label(), "half-storage (S)");
}

TEST(ErrorVsTimeReport, MarkdownHasOneRowPerVariantAndStatesHowItMeasured) {
  const std::string md = render_markdown(sample_report());
  for (const auto& v : sample_report().variants)
    EXPECT_EQ(count(md, "| " + v.precision + " "), 2u) << v.precision;  // specialised and general rows
  EXPECT_NE(md.find("median"), std::string::npos);
  EXPECT_NE(md.find("untimed warm-up"), std::string::npos);
  EXPECT_NE(md.find("1e-06"), std::string::npos) << "the relative error floor is stated";
  EXPECT_NE(md.find("Pareto front"), std::string::npos);
}

TEST(ErrorVsTimeReport, SvgHasOnePointPerVariantAndAPolylineForTheFront) {
  const ErrorVsTimeReport report = sample_report();
  const std::string svg = render_svg(error_vs_time_chart(report));
  EXPECT_EQ(count(svg, "class=\"point\""), report.variants.size());
  EXPECT_EQ(count(svg, "<polyline class=\"series-line\""), 1u);
  const std::smatch front = [&] {
    std::smatch m;
    std::regex_search(svg, m, std::regex("<polyline class=\"series-line\"[^>]* points=\"([^\"]*)\""));
    return m;
  }();
  ASSERT_FALSE(front.empty());
  EXPECT_EQ(count(front[1].str(), ","), 4u) << "four variants on the front: " << front[1];
  for (const auto& v : report.variants) EXPECT_NE(svg.find(">" + v.label() + "</text>"), std::string::npos) << v.label();
  EXPECT_EQ(svg.rfind("</svg>\n"), svg.size() - 7);
}

TEST(SvgChart, RejectsWhatALogAxisCannotShow) {
  Chart chart;
  chart.y.log_scale = true;
  chart.series.push_back({"s", {{1, 0, "zero"}}, MarkerShape::circle, false, ""});
  EXPECT_THROW(render_svg(chart), std::invalid_argument);
  chart.series[0].points[0].y = std::nan("");
  EXPECT_THROW(render_svg(chart), std::invalid_argument);
  chart.series.clear();
  EXPECT_THROW(render_svg(chart), std::invalid_argument);
}

TEST(ErrorVsTimeReport, JsonRoundTripKeepsEveryVariantAndField) {
  ErrorVsTimeReport report = sample_report();
  report.relative_error_floor = 2e-6;  // not the default, so that a field the JSON loses shows
  const ErrorVsTimeReport back = error_vs_time_report_from_json(nlohmann::json::parse(to_json(report).dump()));
  report.variants = sorted_by_kernel_time(report.variants);  // the order every output lists them in
  EXPECT_EQ(back, report) << "written:\n" << to_json(report).dump(1) << "\nread back, written again:\n"
                          << to_json(back).dump(1);
}

TEST(BenchCli, WritesThreeFilesWithEveryVariantMeasured) {
  PHONGCL_REQUIRE_OPENCL(testing::have_opencl_device());
  testing::TempDir dir;
  const auto run = testing::run_phongcl("bench --scene scenes/default/scene.json --runs 2 --report '" +
                                        (dir / "report").string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  for (const char* file : {"report.md", "report.json", "error_vs_time.svg"})
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "report" / file)) << file;

  const auto json = nlohmann::json::parse(testing::read_text(dir / "report" / "report.json"));
  EXPECT_EQ(json.at("runs"), 2);
  std::set<std::string> seen;
  for (const auto& v : json.at("variants")) {
    const std::string label = v.at("precision").get<std::string>() + " " + v.at("kernel").get<std::string>();
    seen.insert(label);
    EXPECT_EQ(v.at("kernel_ms_runs").size(), 2u) << label;
    EXPECT_GT(v.at("kernel_median_ms").get<double>(), 0.0) << label;
    const auto& error = v.at("error");
    EXPECT_GT(error.at("pixels_compared").get<std::size_t>(), 0u) << label;
    EXPECT_EQ(error.at("nonfinite_mismatches"), 0) << label;
    for (const char* field : {"max_abs", "max_rel", "rmse"})
      EXPECT_TRUE(std::isfinite(error.at(field).get<double>())) << label << " " << field;
    // Every variant rounds in float (or to float): its measured error against double is not zero.
    EXPECT_GT(error.at("max_rel").get<double>(), 0.0) << label;
  }
  // double runs exactly where the device the command picked (the default one) has fp64.
  const bool fp64 = pick_device("").info.has_fp64;
  for (const char* precision : {"precise", "fast", "half-storage", "double"})
    for (const char* kernel : {"specialised", "general"})
      EXPECT_EQ(seen.count(std::string(precision) + " " + kernel), precision != std::string("double") || fp64 ? 1u : 0u)
          << precision << " " << kernel;
  EXPECT_EQ(seen.size(), fp64 ? 8u : 6u);
}

// The directory is made before anything is measured, so this needs no device.
TEST(BenchCli, ReportDirectoryThatCannotBeCreatedIsAOneLineError) {
  testing::TempDir dir;
  std::ofstream(dir / "blocker") << "a file, not a directory";
  const auto run = testing::run_phongcl("bench --scene scenes/default/scene.json --runs 1 --report '" +
                                        (dir / "blocker" / "report").string() + "'");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("cannot create report directory"), std::string::npos) << run.err;
  EXPECT_EQ(count(run.err, "\n"), 1u) << run.err;
}

}  // namespace
}  // namespace phongcl
