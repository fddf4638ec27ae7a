// phongcl compare: error of one image against another: linear EXRs by their values, 8-bit PNGs
// (display transforms: ours against Blender's or OpenColorIO's) by their bytes.
#include <png.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <vector>

#include "cli/lab_commands.h"
#include "common/error.h"
#include "image/image.h"

namespace phongcl::cli {

namespace {

struct CompareArguments {
  std::string test_file, expected_file;
  double abs_floor = 1e-6;
  double tolerance = -1.0;  // negative: report only
  int bytes = 1;               // PNGs: a pixel agrees when every channel is within this many levels
  double min_fraction = -1.0;  // PNGs: exit non-zero when fewer pixels agree; negative: report only
};

struct Rgb8 {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

Rgb8 read_png_rgb(const std::string& file) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, file.c_str())) throw InputError(file, std::string("not a readable PNG (") + png.message + ")");
  png.format = PNG_FORMAT_RGB;  // alpha composited over black: previews are opaque
  Rgb8 image{static_cast<int>(png.width), static_cast<int>(png.height), std::vector<std::uint8_t>(PNG_IMAGE_SIZE(png))};
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr))
    throw InputError(file, std::string("cannot decode the PNG (") + png.message + ")");
  return image;
}

bool is_png(const std::string& file) { return file.size() > 4 && file.compare(file.size() - 4, 4, ".png") == 0; }

void compare_pngs(const CompareArguments& args) {
  const Rgb8 test = read_png_rgb(args.test_file), expected = read_png_rgb(args.expected_file);
  if (test.width != expected.width || test.height != expected.height)
    throw InputError(args.test_file, "size " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                                         " does not match " + args.expected_file);
  const std::size_t pixels = static_cast<std::size_t>(test.width) * test.height;
  std::size_t identical = 0, within = 0, worst_pixel = 0;
  int worst = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    int difference = 0;
    for (int c = 0; c < 3; ++c) difference = std::max(difference, std::abs(int(test.rgb[3 * i + c]) - int(expected.rgb[3 * i + c])));
    identical += difference == 0;
    within += difference <= args.bytes;
    if (difference > worst) worst = difference, worst_pixel = i;
  }
  const double fraction = static_cast<double>(within) / static_cast<double>(pixels);
  std::printf(
      "phongcl compare: %s against %s\n"
      "  pixels     %zu (%d x %d)\n"
      "  identical  %.3f%%\n"
      "  within %d/255 %.3f%%\n"
      "  worst      %d/255 at pixel (%zu, %zu)\n",
      args.test_file.c_str(), args.expected_file.c_str(), pixels, test.width, test.height,
      100.0 * static_cast<double>(identical) / static_cast<double>(pixels), args.bytes, 100.0 * fraction, worst,
      worst_pixel % test.width, worst_pixel / test.width);
  if (args.min_fraction >= 0.0 && fraction < args.min_fraction)
    throw std::runtime_error("compare: " + std::to_string(100.0 * fraction) + "% of pixels within " +
                             std::to_string(args.bytes) + "/255, fewer than --min-fraction " + std::to_string(args.min_fraction));
}

void run_compare(const CompareArguments& args) {
  if (is_png(args.test_file) && is_png(args.expected_file)) return compare_pngs(args);
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
  command->add_option("test", args->test_file, "Image to check (EXR; or PNG, compared byte by byte)")->required();
  command->add_option("expected", args->expected_file, "Expected image (EXR, or PNG)")->required();
  command->add_option("--abs-floor", args->abs_floor, "Relative error is |t - e| / max(|e|, floor) (default 1e-6)");
  command->add_option("--tolerance", args->tolerance, "Exit non-zero if the max relative error exceeds this");
  command->add_option("--bytes", args->bytes, "PNGs: a pixel agrees when each channel differs by at most this (default 1)")
      ->check(CLI::Range(0, 255));
  command->add_option("--min-fraction", args->min_fraction, "PNGs: exit non-zero if fewer pixels agree (e.g. 0.999)");
  command->callback([args] { run_compare(*args); });
}

}  // namespace phongcl::cli
