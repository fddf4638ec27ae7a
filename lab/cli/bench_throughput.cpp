// phongcl bench --throughput: the OpenCL kernel in each precision variant against the C++ peers
// (cpp-scalar, cpp-simd, halide) on the same frames, with the machine's limits measured in the same run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cl/compute_context.h"
#include "cli/bench_arguments.h"
#include "cli/throughput_report.h"
#include "peers/halide_peer.h"
#include "peers/light_sweep.h"
#include "peers/machine_limits.h"
#include "peers/peers.h"
#include "peers/work_model.h"
#include "reference/reference.h"
#include "report/elapsed.h"
#include "report/report_files.h"
#include "shading/phong_shader.h"

namespace phongcl::cli {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kSweepSizeLights = 16;                 // lights for the image-size sweep
constexpr double kMeasurementBudgetMs = 5000.0;      // timed runs per measurement, roughly
constexpr int kMinimumRuns = 3;
// cpp-scalar and the double reference run on every n-th row of frames larger than this many
// pixel-lights (about a second each here).
constexpr double kSampledPixelLights = 1e7;

struct Case {
  int width = 0, height = 0, lights = 0;
};

std::vector<int> parse_list(const std::string& text, const char* what) {
  std::vector<int> values;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    std::size_t used = 0;
    int value = -1;
    try {
      value = std::stoi(item, &used);
    } catch (const std::exception&) {
    }
    if (used != item.size() || value < 0) throw std::invalid_argument(std::string(what) + ": not a count: '" + item + "'");
    values.push_back(value);
  }
  return values;
}

std::vector<std::pair<int, int>> parse_sizes(const std::string& text) {
  std::vector<std::pair<int, int>> sizes;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto x = item.find('x');
    int width = 0, height = 0;
    try {
      if (x != std::string::npos) width = std::stoi(item.substr(0, x)), height = std::stoi(item.substr(x + 1));
    } catch (const std::exception&) {
    }
    if (width < 1 || height < 1) throw std::invalid_argument("--sizes: not WIDTHxHEIGHT: '" + item + "'");
    sizes.emplace_back(width, height);
  }
  return sizes;
}

// Default: the light sweep at the G-buffer's own size, then the size sweep at 16 lights. With only
// --lights or only --sizes, that sweep; with both, every combination.
std::vector<Case> plan_cases(const BenchArguments& args, const GBuffer& gbuffer) {
  const std::vector<int> lights = parse_list(args.lights.empty() ? "0,1,4,16,64,256" : args.lights, "--lights");
  const auto sizes = parse_sizes(args.sizes.empty() ? "256x256,1920x1080,3840x2160,7680x4320" : args.sizes);
  std::vector<Case> cases;
  auto add = [&](int w, int h, int l) {
    const Case c{w, h, l};
    if (std::none_of(cases.begin(), cases.end(), [&](const Case& o) { return o.width == w && o.height == h && o.lights == l; })) {
      cases.push_back(c);
    }
  };
  if (!args.sizes.empty() && !args.lights.empty()) {
    for (auto [w, h] : sizes) for (int l : lights) add(w, h, l);
    return cases;
  }
  if (args.sizes.empty()) for (int l : lights) add(gbuffer.width, gbuffer.height, l);
  if (args.lights.empty()) for (auto [w, h] : sizes) add(w, h, kSweepSizeLights);
  return cases;
}

std::vector<bool> shaded_mask(const GBuffer& gbuffer) {
  std::vector<bool> mask(gbuffer.pixel_count());
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = classify_pixel(gbuffer, i) == PixelClass::shaded;
  return mask;
}

// Every n-th row of a case, with n chosen so the slow implementations (the double reference and
// cpp-scalar, single-threaded) shade about kSampledPixelLights there; n = 1 for small cases.
struct SampledRows {
  int step = 1;
  GBuffer gbuffer;
  Image reference;  // the double reference on these rows
  std::vector<bool> shaded;

  SampledRows(const Scene& scene, const GBuffer& frame, int lights) {
    const double pixel_lights = static_cast<double>(frame.pixel_count()) * std::max(lights, 1);
    step = std::max(1, static_cast<int>(std::ceil(pixel_lights / kSampledPixelLights)));
    gbuffer = every_nth_row(frame, step);
    reference = reference_image(scene, gbuffer);
    shaded = shaded_mask(gbuffer);
  }
  double max_rel_err_of_rows(const Image& rows) const { return compare_images(rows, reference, 1e-6, shaded).max_rel; }
  double max_rel_err_of_frame(const Image& frame) const { return max_rel_err_of_rows(every_nth_row(frame, step)); }
};

class ThroughputBench {
 public:
  ThroughputBench(int runs, MachineLimits machine, PhongShader& shader, std::optional<std::filesystem::path> halide_peer)
      : runs_(runs), machine_(std::move(machine)), shader_(shader), halide_peer_(std::move(halide_peer)) {}

  void run_case(const Scene& scene, const GBuffer& gbuffer, int lights) {
    int points = 0, directionals = 0;
    for (const Light& light : scene.lights) (light.type == LightType::point ? points : directionals)++;
    const double flops = flops_per_pixel(points, directionals);
    const SampledRows rows(scene, gbuffer, lights);
    const PackedScene packed = pack_scene(scene);

    {  // cpp-scalar on the sampled rows (the whole frame when small), times scaled to the whole frame
      const PackedFrame frame = pack_frame(rows.gbuffer, scene);
      Image output = image_like(rows.gbuffer);
      const double scale = static_cast<double>(gbuffer.pixel_count()) / rows.gbuffer.pixel_count();
      const RunStats time = measure(
          [&] {
            const auto start = Clock::now();
            shade_scalar(frame, packed, output.rgba.data());
            return elapsed_ms(start) * scale;
          },
          rows.step > 1 ? kMinimumRuns : runs_);
      ThroughputResult& r = add("cpp-scalar", "float", gbuffer, lights, time, bytes_per_pixel(false, points + directionals), flops, 1.0);
      r.timed_row_step = rows.step;
      record_error(r, rows, rows.max_rel_err_of_rows(output));
    }
    const PackedFrame frame = pack_frame(gbuffer, scene);
    {  // cpp-simd on the whole frame
      Image output = image_like(gbuffer);
      const RunStats time = measure(
          [&] {
            const auto start = Clock::now();
            shade_simd(frame, packed, output.rgba.data());
            return elapsed_ms(start);
          },
          runs_);
      ThroughputResult& r = add("cpp-simd", "float", gbuffer, lights, time, bytes_per_pixel(false, points + directionals), flops, 1.0);
      record_error(r, rows, rows.max_rel_err_of_frame(output));
    }
    {  // halide on the whole frame, in its own process
      const double bytes = bytes_per_pixel(false, points + directionals);
      if (!halide_peer_) {
        add_not_run("halide", gbuffer, lights, "SKIP: Halide not installed (no " + std::string(kHalidePeerExecutable) + " beside phongcl-lab)");
      } else {
        Image output = image_like(gbuffer);
        try {
          const HalidePeerRun run = run_halide_peer(*halide_peer_, frame, packed, runs_, kMeasurementBudgetMs, output.rgba.data());
          ThroughputResult& r = add("halide", "float", gbuffer, lights, summarize(run.times_ms), bytes, flops, 1.0);
          r.schedule = run.schedule;
          r.compile_ms = run.compile_ms;
          record_error(r, rows, rows.max_rel_err_of_frame(output));
        } catch (const std::runtime_error& e) {  // the other rows still count; this one says why it has no figures
          std::cerr << "\n  halide     " << e.what() << "\n";
          add_not_run("halide", gbuffer, lights, std::string("FAILED: ") + e.what());
        }
      }
    }
    for (Precision precision : all_precisions()) {
      if (precision == Precision::double_precision && !shader_.compute().device.info.has_fp64) continue;
      const ShadeOptions options{precision, true};
      ShadeResult last;
      std::vector<double> end_to_end;
      const RunStats kernel = measure(
          [&] {
            last = shader_.shade(scene, gbuffer, options);
            end_to_end.push_back(last.timings.total_ms);
            return last.timings.kernel_ms;
          },
          runs_);
      end_to_end.erase(end_to_end.begin());  // the warm-up's
      const bool half = precision == Precision::half_storage;
      const double peak_share = precision == Precision::double_precision ? 0.5 : 1.0;  // 8 double lanes, not 16
      ThroughputResult& r = add("opencl", to_string(precision), gbuffer, lights, kernel,
                                bytes_per_pixel(half, points + directionals), flops, peak_share);
      r.end_to_end = summarize(end_to_end);
      record_error(r, rows, rows.max_rel_err_of_frame(last.image));
    }
  }

  const std::vector<ThroughputResult>& results() const { return results_; }

 private:
  // One untimed warm-up (for OpenCL it includes the kernel build), then timed runs: `runs` of
  // them, or fewer (never below kMinimumRuns) where the first timed run says they would exceed the budget.
  static RunStats measure(const std::function<double()>& run, int runs) {
    run();
    const auto first_start = Clock::now();
    std::vector<double> times{run()};
    const double run_ms = std::max(elapsed_ms(first_start), 1e-3);
    const int count = std::clamp(static_cast<int>(kMeasurementBudgetMs / run_ms), std::min(kMinimumRuns, runs), runs);
    while (static_cast<int>(times.size()) < count) times.push_back(run());
    return summarize(times);
  }

  ThroughputResult& add(const std::string& impl, const std::string& variant, const GBuffer& gbuffer, int lights,
                        const RunStats& time, double bytes_per_pixel, double flops, double peak_share) {
    ThroughputResult r;
    r.impl = impl;
    r.variant = variant;
    r.lights = lights;
    r.width = gbuffer.width;
    r.height = gbuffer.height;
    r.time = time;
    r.bytes_per_pixel = bytes_per_pixel;
    r.flops_per_pixel = flops;
    const double pixels = static_cast<double>(gbuffer.pixel_count());
    r.mpix_per_s = pixels / (time.median_ms * 1e3);
    r.mpix_lights_per_s = r.mpix_per_s * lights;
    r.roofline_mpix_per_s =
        roofline_pixels_per_second(machine_.bandwidth_gbs * 1e9, machine_.fma_gflops * 1e9 * peak_share, bytes_per_pixel, flops) / 1e6;
    r.roofline_fraction = r.mpix_per_s / r.roofline_mpix_per_s;
    results_.push_back(r);
    return results_.back();
  }

  void add_not_run(const std::string& impl, const GBuffer& gbuffer, int lights, const std::string& reason) {
    ThroughputResult r;
    r.impl = impl;
    r.variant = "float";
    r.lights = lights;
    r.width = gbuffer.width;
    r.height = gbuffer.height;
    r.not_run = reason;
    results_.push_back(r);
  }

  static void record_error(ThroughputResult& r, const SampledRows& rows, double max_rel_err) {
    r.max_rel_err = max_rel_err;
    r.error_row_step = rows.step;
  }

  int runs_;
  MachineLimits machine_;
  PhongShader& shader_;
  std::optional<std::filesystem::path> halide_peer_;
  std::vector<ThroughputResult> results_;
};

// /proc/loadavg's three averages, "n/a" where there is none: every figure here depends on it.
}  // namespace

void run_throughput_bench(const BenchArguments& args) {
  const Scene scene = args.inputs.load_scene();
  const GBuffer gbuffer = args.inputs.load_gbuffer(scene);
  const std::vector<Case> cases = plan_cases(args, gbuffer);
  ProgramCache cache(ProgramCache::default_directory());
  PhongShader shader(make_compute_context(pick_device(args.device)), cache);
  const std::string device = describe(shader.compute().device.info);

  std::cout << "phongcl bench --throughput: " << scene.source.string() << " + " << gbuffer.source.string() << "\n"
            << "  device     " << device << "\n  measuring  memory bandwidth and FMA peak..." << std::flush;
  const MachineLimits machine = measure_machine_limits();
  std::cout << " " << machine.bandwidth_gbs << " GB/s, " << machine.fma_gflops << " GFLOP/s on " << machine.cores
            << " cores (" << machine.cpu << ")\n";

  // The Halide peer is built beside phongcl-lab when Halide is installed.
  const auto halide_peer = find_halide_peer(std::filesystem::read_symlink("/proc/self/exe").parent_path());
  std::cout << "  halide     " << (halide_peer ? halide_peer->string() : "not installed: its rows say SKIP") << "\n";
  const std::string load_at_start = load_average();
  std::cout << "  load       " << load_at_start << " (1, 5, 15 min; the machine may be shared)\n";
  ThroughputBench bench(args.runs, machine, shader, halide_peer);
  for (const Case& c : cases) {
    std::cout << "  case       " << c.width << "x" << c.height << ", " << c.lights << " lights" << std::flush;
    const auto start = Clock::now();
    const GBuffer frame = c.width == gbuffer.width && c.height == gbuffer.height ? gbuffer : resample_nearest(gbuffer, c.width, c.height);
    bench.run_case(with_generated_lights(scene, c.lights), frame, c.lights);
    std::cout << " (" << static_cast<int>(elapsed_ms(start) / 1000) << " s)\n";
  }
  const std::string load = "load average " + load_at_start + " at the start, " + load_average() + " at the end";
  std::cout << "\n" << markdown_table(bench.results()) << halide_note(bench.results()) << "  " << load << "\n";
  if (!args.json_file.empty()) {
    const std::filesystem::path json_file = args.json_file;
    if (json_file.has_parent_path()) std::filesystem::create_directories(json_file.parent_path());
    write_text_file(json_file, results_json(machine, bench.results(), load));
  }
  if (!args.report_dir.empty()) {
    const std::string inputs = "`" + scene.source.string() + "` + `" + gbuffer.source.string() + "`";
    write_throughput_report(args.report_dir, machine, device, inputs, load, bench.results());
    std::cout << "  wrote      " << args.report_dir << "/report.md, results.json, mpix_lights_vs_lights.svg\n";
  }
}

}  // namespace phongcl::cli
