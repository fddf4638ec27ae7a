// phongcl bench --display: the display transforms of 8-bit outputs (color/display.h) on one shaded
// frame, against OpenColorIO's own CPU processor of the same view on the same values: time on
// every core and on one, and how many bytes agree.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>
#include <phongcl/relighter.hpp>

#include "cli/bench_arguments.h"
#include "cli/format.h"
#include "color/display.h"
#include "color/display_processor.h"
#include "common/error.h"
#include "peers/machine_limits.h"  // load_average
#include "raycast/raycast.h"
#include "report/elapsed.h"
#include "report/statistics.h"
#include "scene/json_reader.h"  // format_number

namespace phongcl::cli {

namespace {

namespace OCIO = OCIO_NAMESPACE;
using Clock = std::chrono::steady_clock;

struct Case {
  std::string config;  // as --ocio takes it
  DisplaySettings settings;
  std::string name;
};

struct CaseResult {
  std::string name, pipeline;
  double build_ms = 0, wall_ms = 0, cpu_ms = 0, one_thread_ms = 0, ocio_ms = 0;
  double equal = 0, within_one = 0;  // fractions of channel bytes against OpenColorIO's
  int worst = 0;
  bool skipped = false;
  std::string why;
};

double process_cpu_ms() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

double thread_cpu_ms() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

std::vector<Case> cases(const glm::dvec3& background) {
  const auto make = [&](const std::string& config, const std::string& view, const std::string& look, double exposure) {
    DisplaySettings settings;
    settings.view = view;
    settings.look = look;
    settings.exposure_stops = exposure;
    settings.background = background;
    std::string name = config + " " + view + (look.empty() ? "" : " + " + look);
    if (exposure != 0.0) name += ", exposure " + format_number(exposure);
    return Case{config, settings, name};
  };
  return {make("builtin", "reinhard", "", 0), make("builtin", "aces", "", 0), make("builtin", "clamp", "", 0),
          make("blender", "Standard", "", 0), make("blender", "Filmic", "", 0), make("blender", "Filmic", "", 1.5),
          make("blender", "Filmic", "High Contrast", 0), make("blender", "Filmic", "Very Low Contrast", -1)};
}

// What the display transform feeds the processor: the image over the background, exposed.
std::vector<float> flattened(const Image& image, const DisplaySettings& settings) {
  std::vector<float> rgb(3 * image.pixel_count());
  const float scale = static_cast<float>(std::exp2(settings.exposure_stops));
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    const float* p = image.pixel(i);
    const float alpha = std::clamp(p[3], 0.0f, 1.0f);
    for (int c = 0; c < 3; ++c)
      rgb[3 * i + c] = ((alpha > 0.0f ? p[c] : 0.0f) + (1.0f - alpha) * static_cast<float>(settings.background[c])) * scale;
  }
  return rgb;
}

std::uint8_t to_byte(float v) { return v > 0.0f ? (v < 1.0f - 0.5f / 255.0f ? static_cast<std::uint8_t>(v * 255.0f + 0.5f) : 255) : 0; }

CaseResult run_case(const Case& c, const Image& image, int runs) {
  CaseResult result;
  result.name = c.name;
  std::optional<ColorConfig> config;
  try {
    config = ColorConfig::load(c.config);
  } catch (const InputError& error) {
    result.skipped = true;
    result.why = error.what();
    return result;
  }
  const auto build_start = Clock::now();
  const DisplayTransform display(*config, c.settings);
  result.build_ms = elapsed_ms(build_start);
  result.pipeline = display.pipeline();
  std::vector<std::uint8_t> bytes = display.encode(image);  // warm-up
  std::vector<double> wall, cpu, one;
  for (int r = 0; r < runs; ++r) {
    const auto start = Clock::now();
    const double cpu_start = process_cpu_ms();
    bytes = display.encode(image);
    cpu.push_back(process_cpu_ms() - cpu_start);
    wall.push_back(elapsed_ms(start));
    const double thread_start = thread_cpu_ms();
    display.encode_rows(image, 0, image.height, bytes.data());
    one.push_back(thread_cpu_ms() - thread_start);
  }
  result.wall_ms = median(wall);
  result.cpu_ms = median(cpu);
  result.one_thread_ms = median(one);

  std::vector<float> exact = flattened(image, c.settings);
  const OCIO::ConstCPUProcessorRcPtr ocio =
      display_processor(*config, display.display(), display.view(), display.look())->getDefaultCPUProcessor();
  OCIO::PackedImageDesc packed(exact.data(), image.width, image.height, 3);
  const double ocio_start = thread_cpu_ms();
  ocio->apply(packed);
  result.ocio_ms = thread_cpu_ms() - ocio_start;
  std::size_t equal = 0, within = 0;
  for (std::size_t i = 0; i < image.pixel_count(); ++i)
    for (int ch = 0; ch < 3; ++ch) {
      const int difference = std::abs(int(bytes[4 * i + ch]) - int(to_byte(std::clamp(exact[3 * i + ch], -3e38f, 3e38f))));
      equal += difference == 0;
      within += difference <= 1;
      result.worst = std::max(result.worst, difference);
    }
  result.equal = static_cast<double>(equal) / (3.0 * image.pixel_count());
  result.within_one = static_cast<double>(within) / (3.0 * image.pixel_count());
  return result;
}

}  // namespace

void run_display_bench(const BenchArguments& args) {
  const Scene scene = args.inputs.load_scene();
  const bool has_gbuffer = !args.inputs.gbuffer_file.empty() || !scene.gbuffer.empty();
  GBuffer gbuffer = has_gbuffer ? args.inputs.load_gbuffer(scene) : generate_gbuffer(scene);
  RelighterOptions options;
  options.device = args.device;
  Relighter relighter(scene, std::move(gbuffer), options);
  const Image image = relighter.shade();
  const std::string load_before = load_average();
  const unsigned threads = std::thread::hardware_concurrency();  // what DisplayTransform::encode runs on
  std::cout << "phongcl bench --display: " << scene.source.string() << ", " << image.width << " x " << image.height << " ("
            << with_commas(image.pixel_count()) << " pixels), " << threads << " threads; load average " << load_before << "\n"
            << "  per case: the median of " << args.runs << " runs after a warm-up; 'all' encodes in row blocks on every "
               "thread (wall clock, and the process's CPU time), 'one' the whole frame on one thread (CPU time); "
               "OpenColorIO: its default CPU processor of the same view on the same values, one thread, one run; bytes "
               "against OpenColorIO's (rounded as Blender rounds)\n";
  nlohmann::json json = nlohmann::json::array();
  for (const Case& c : cases(scene.background)) {
    const CaseResult r = run_case(c, image, args.runs);
    if (r.skipped) {
      std::cout << "  " << r.name << ": SKIP (" << r.why << ")\n";
      continue;
    }
    char line[512];
    std::snprintf(line, sizeof line,
                  "  %-42s all %6.2f ms wall (%6.2f ms CPU), one %6.2f ms; OpenColorIO %7.1f ms (%.0fx); bytes equal "
                  "%.3f%%, within 1/255 %.3f%%, worst %d; built in %.0f ms: %s\n",
                  r.name.c_str(), r.wall_ms, r.cpu_ms, r.one_thread_ms, r.ocio_ms, r.ocio_ms / r.one_thread_ms,
                  100 * r.equal, 100 * r.within_one, r.worst, r.build_ms, r.pipeline.c_str());
    std::cout << line;
    json.push_back({{"case", r.name}, {"wall_ms", r.wall_ms}, {"cpu_ms", r.cpu_ms}, {"one_thread_ms", r.one_thread_ms},
                    {"ocio_one_thread_ms", r.ocio_ms}, {"bytes_equal", r.equal}, {"bytes_within_one", r.within_one},
                    {"worst", r.worst}, {"build_ms", r.build_ms}, {"pipeline", r.pipeline}});
  }
  std::cout << "  load average after " << load_average() << "\n";
  if (!args.json_file.empty()) {
    std::ofstream out(args.json_file);
    out << nlohmann::json{{"width", image.width}, {"height", image.height}, {"threads", threads},
                          {"load_before", load_before}, {"cases", json}}
               .dump(2)
        << "\n";
    if (!out) throw InputError(args.json_file, "cannot write");
  }
}

}  // namespace phongcl::cli
