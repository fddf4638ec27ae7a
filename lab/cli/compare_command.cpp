// phongcl compare: error of one image against another.
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "cli/lab_commands.h"
#include "common/error.h"
#include "image/image.h"

namespace phongcl::cli {

namespace {

struct CompareArguments {
  std::string test_file, expected_file;
  double abs_floor = 1e-6;
  double tolerance = -1.0;  // negative: report only
};

void run_compare(const CompareArguments& args) {
  const Image test = read_exr(args.test_file);
  const Image expected = read_exr(args.expected_file);
  if (test.width != expected.width || test.height != expected.height) {
    throw InputError(args.test_file, "size " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                                         " does not match " + args.expected_file + " (" + std::to_string(expected.width) +
                                         "x" + std::to_string(expected.height) + ")");
  }
  const ErrorStats stats = compare_images(test, expected, args.abs_floor);
  static const char* channel_names[] = {"R", "G", "B"};
  std::printf(
      "phongcl compare: %s against %s\n"
      "  pixels     %zu\n"
      "  max abs    %.3g\n"
      "  max rel    %.3g (relative to max(|expected|, %.0e))\n"
      "  RMSE       %.3g\n"
      "  PSNR       %.1f dB\n"
      "  worst      pixel (%d, %d) %s: %.9g, expected %.9g\n",
      args.test_file.c_str(), args.expected_file.c_str(), stats.pixels_compared, stats.max_abs, stats.max_rel,
      args.abs_floor, stats.rmse, stats.psnr_db, stats.worst_x, stats.worst_y, channel_names[stats.worst_channel],
      stats.worst_test, stats.worst_expected);
  if (stats.nonfinite_mismatches > 0) std::printf("  non-finite mismatches: %zu\n", stats.nonfinite_mismatches);
  if (args.tolerance >= 0.0 && stats.nonfinite_mismatches > 0) {
    throw std::runtime_error("compare: " + std::to_string(stats.nonfinite_mismatches) +
                             " values are non-finite in one image and not the other");
  }
  if (args.tolerance >= 0.0 && stats.max_rel > args.tolerance) {
    throw std::runtime_error("compare: max relative error " + std::to_string(stats.max_rel) + " exceeds --tolerance " +
                             std::to_string(args.tolerance));
  }
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArguments>();
  CLI::App* command = app.add_subcommand("compare", "Error of an image against an expected one (e.g. the reference)");
  command->add_option("test", args->test_file, "Image to check (EXR)")->required();
  command->add_option("expected", args->expected_file, "Expected image (EXR)")->required();
  command->add_option("--abs-floor", args->abs_floor, "Relative error is |t - e| / max(|e|, floor) (default 1e-6)");
  command->add_option("--tolerance", args->tolerance, "Exit non-zero if the max relative error exceeds this");
  command->callback([args] { run_compare(*args); });
}

}  // namespace phongcl::cli
