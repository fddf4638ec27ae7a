// phongcl bench --many-lights: tiled light culling against the unculled kernel and a C++ peer doing
// the same tiled culling, from 64 to 10,000 ranged point and spot lights on one frame.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <omp.h>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "cl/compute_context.h"
#include "cli/bench_arguments.h"
#include "cli/many_lights_report.h"
#include "peers/light_sweep.h"
#include "peers/machine_limits.h"
#include "peers/many_lights.h"
#include "peers/peers.h"
#include "raycast/raycast.h"
#include "reference/reference.h"
#include "report/elapsed.h"
#include "report/report_files.h"
#include "shading/phong_shader.h"
#include "shading/tile_culling.h"

namespace phongcl::cli {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kTileSize = 16;

// How many lights reach an average shaded pixel, and a shaded pixel of its tile.
struct Reach {
  double pixel = 0.0, tile = 0.0;
};
constexpr double kSingleRunMs = 10000.0;      // a run longer than this is timed once
constexpr double kReferencePixelLights = 3e6;  // the double reference's sample of rows (a few seconds here)
constexpr int kUnculledRateLights = 16;        // the unculled kernel's pixel-lights/s is quoted here

std::vector<int> parse_counts(const std::string& text) {
  std::vector<int> counts;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    std::size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(item, &used);
    } catch (const std::exception&) {
    }
    if (used != item.size() || value < 1) throw std::invalid_argument("--lights: not a light count >= 1: '" + item + "'");
    counts.push_back(value);
  }
  return counts;
}

// One untimed warm-up, then `runs` timed ones; where the first run took over 10 s it is the single
// timed run (its kernel time excludes the build, which happens before the kernel is enqueued).
template <typename Run>
std::vector<double> time_runs(int runs, Run run, bool& single) {
  const double first = run();
  single = first > kSingleRunMs;
  if (single) return {first};
  std::vector<double> times;
  for (int r = 0; r < runs; ++r) times.push_back(run());
  return times;
}

// The double reference on every n-th row, n chosen for about kReferencePixelLights.
struct ReferenceRows {
  int step = 1;
  Image image;
  std::vector<bool> shaded;
  ReferenceRows(const Scene& scene, const GBuffer& frame) {
    const double pixel_lights = static_cast<double>(frame.pixel_count()) * static_cast<double>(scene.lights.size());
    step = std::max(1, static_cast<int>(std::ceil(pixel_lights / kReferencePixelLights)));
    const GBuffer rows = every_nth_row(frame, step);
    image = reference_image(scene, rows);
    shaded.resize(rows.pixel_count());
    for (std::size_t i = 0; i < shaded.size(); ++i) shaded[i] = classify_pixel(rows, i) == PixelClass::shaded;
  }
  double error_of(const Image& frame) const { return compare_images(every_nth_row(frame, step), image, 1e-6, shaded).max_rel; }
};

class ManyLightsBench {
 public:
  ManyLightsBench(PhongShader& shader, const GBuffer& gbuffer, int runs) : shader_(shader), gbuffer_(gbuffer), runs_(runs) {
    for (std::size_t i = 0; i < gbuffer.pixel_count(); ++i) shaded_ += classify_pixel(gbuffer, i) == PixelClass::shaded;
  }

  void unculled(const Scene& scene, Reach reach, const ReferenceRows* reference) {
    ShadeOptions options;
    options.culling = Culling::none;
    ShadeResult last;
    ManyLightsResult r;
    const std::vector<double> times = time_runs(runs_, [&] {
      last = shader_.shade(scene, gbuffer_, options);
      return last.timings.kernel_ms;
    }, r.single_run);
    r.impl = "opencl-unculled";
    r.lights = static_cast<int>(scene.lights.size());
    r.time = summarize(times);
    set_figures(r, static_cast<double>(shaded_) * r.lights, reach,
                reference ? std::optional(reference->error_of(last.image)) : std::nullopt);
    finish(r);
  }

  // The tiled kernel, and cpp-tiled at its default schedule and, with `sweep`, at every schedule of a
  // grid, the fastest reported as "cpp-tiled-best". They take turns, one run each per round after a
  // warm-up each, so that the machine's drift (10-20% over a minute here) lands on all of them alike.
  void tiled(const Scene& scene, Reach reach, const ReferenceRows& reference, bool sweep) {
    ShadeOptions options;
    options.culling = Culling::tiled;
    options.tile_size = kTileSize;
    ShadeResult last;
    std::vector<double> kernel_times, culling;
    const auto run_kernel = [&] {
      last = shader_.shade(scene, gbuffer_, options);
      kernel_times.push_back(last.timings.kernel_ms);
      culling.push_back(last.culling.culling_ms);
    };
    const PackedFrame frame = pack_frame(gbuffer_, scene);
    const PackedScene packed = pack_scene(scene);
    std::vector<PeerTiming> timings{{TiledPeerSchedule{}}};
    if (sweep)
      for (int tile_size : {8, 16, 32})
        for (int coarse_tiles : {4, 8, 16})
          for (int tiles_per_task : {1, 4, 16})
            if (TiledPeerSchedule schedule{tile_size, coarse_tiles, tiles_per_task}; schedule != timings.front().schedule)
              timings.push_back({schedule});
    Image image = image_like(gbuffer_);
    const auto run = [&](PeerTiming& timing) {
      const TiledPeerStats stats = shade_tiled(frame, packed, gbuffer_.width, gbuffer_.height, timing.schedule, image.pixel(0));
      timing.times.push_back(stats.culling_ms + stats.shading_ms);
      timing.culling.push_back(stats.culling_ms);
      timing.kept_pairs = stats.kept_pairs;
      timing.max_rel_err = reference.error_of(image);
    };
    // The warm-ups, each kept as the one timed run where it took over 10 s (as time_runs).
    const auto warm_up = [](std::vector<double>& times, std::vector<double>& culling, const auto& run_once) {
      run_once();
      const bool single = times.back() > kSingleRunMs;
      if (!single) times.clear(), culling.clear();
      return single;
    };
    const bool kernel_single = warm_up(kernel_times, culling, run_kernel);
    for (PeerTiming& timing : timings) timing.single_run = warm_up(timing.times, timing.culling, [&] { run(timing); });
    for (int round = 0; round < runs_; ++round) {
      // The peer's idle OpenMP workers spin after its parallel regions (libgomp's GOMP_SPINCOUNT,
      // host/common/host_threads.h), on the cores the kernel runs on: they are let go to sleep first.
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      if (!kernel_single) run_kernel();
      for (PeerTiming& timing : timings)
        if (!timing.single_run) run(timing);
    }
    const auto lights = static_cast<int>(scene.lights.size());
    ManyLightsResult r;
    r.impl = "opencl-tiled";
    r.lights = lights;
    r.single_run = kernel_single;
    r.time = summarize(kernel_times);
    r.culling_ms = summarize(culling).median_ms;
    r.mean_lights_per_tile = last.culling.mean_lights_per_tile();
    r.mean_holding_per_tile = last.culling.mean_holding_per_tile();
    set_figures(r, last.culling.kept_pairs, reach, reference.error_of(last.image));
    finish(r);
    finish(peer_result(timings.front(), "cpp-tiled", lights, reach));
    if (!sweep) return;
    for (const PeerTiming& timing : timings)
      std::cout << "      " << describe(timing.schedule) << ": " << summarize(timing.times).median_ms << " ms\n";
    const auto fastest = std::min_element(timings.begin(), timings.end(), [](const PeerTiming& a, const PeerTiming& b) {
      return summarize(a.times).median_ms < summarize(b.times).median_ms;
    });
    finish(peer_result(*fastest, "cpp-tiled-best", lights, reach));
  }

  const std::vector<ManyLightsResult>& results() const { return results_; }

 private:
  struct PeerTiming {
    TiledPeerSchedule schedule;
    std::vector<double> times{}, culling{};
    double kept_pairs = 0.0;
    std::optional<double> max_rel_err{};
    bool single_run = false;
  };

  ManyLightsResult peer_result(const PeerTiming& timing, const std::string& impl, int lights, Reach reach) const {
    ManyLightsResult r;
    r.impl = impl;
    r.schedule = describe(timing.schedule);
    r.lights = lights;
    r.single_run = timing.single_run;
    r.time = summarize(timing.times);
    r.culling_ms = summarize(timing.culling).median_ms;
    set_figures(r, timing.kept_pairs, reach, timing.max_rel_err);
    return r;
  }

  void set_figures(ManyLightsResult& r, double pairs, Reach reach, std::optional<double> error) const {
    r.mean_lights_per_pixel = shaded_ ? pairs / static_cast<double>(shaded_) : 0.0;
    r.mean_lights_reaching = reach.pixel;
    r.mean_lights_reaching_tile = reach.tile;
    r.effective_mpix_lights_per_s = pairs / (r.time.median_ms * 1e-3) / 1e6;
    r.max_rel_err = error;
  }

  void finish(const ManyLightsResult& r) {
    std::cout << "    " << r.impl << ": " << r.time.median_ms << " ms (" << r.time.runs << " runs"
              << (r.single_run ? ", one run: over 10 s" : "") << "), " << r.mean_lights_per_pixel << " lights/pixel, "
              << r.effective_mpix_lights_per_s << " effective Mpix-lights/s"
              << (r.schedule.empty() ? "" : "; " + r.schedule) << "\n";
    results_.push_back(r);
  }

  PhongShader& shader_;
  const GBuffer& gbuffer_;
  int runs_;
  std::size_t shaded_ = 0;
  std::vector<ManyLightsResult> results_;
};

}  // namespace

void run_many_lights_bench(const BenchArguments& args) {
  if (!args.report_dir.empty()) create_report_directory(args.report_dir);
  const Scene scene = args.inputs.load_scene();
  // The bundled 1080p scene's G-buffer is not in the repository: ray-cast it when it is missing.
  const bool has_gbuffer = !args.inputs.gbuffer_file.empty() || std::filesystem::exists(scene.gbuffer);
  const GBuffer gbuffer = has_gbuffer ? args.inputs.load_gbuffer(scene) : generate_gbuffer(scene);
  ProgramCache cache(ProgramCache::default_directory());
  PhongShader shader(make_compute_context(pick_device(args.device)), cache);
  const int list_rows = static_cast<int>(light_list_layout(gbuffer.width, gbuffer.height, kTileSize).grid.tile_rows);
  ManyLightsMachine machine{cpu_model_name(), describe(shader.compute().device.info), load_average(),
                            omp_get_max_threads(), gbuffer.width, gbuffer.height, kTileSize, list_rows,
                            "`" + scene.source.string() + "`" + (has_gbuffer ? "" : " (G-buffer ray-cast)")};
  std::cout << "phongcl bench --many-lights: " << scene.source.string() << ", " << gbuffer.width << "x" << gbuffer.height
            << "\n  device     " << machine.device << "\n  load       " << machine.loadavg << "\n";

  ManyLightsBench bench(shader, gbuffer, std::max(args.runs, 5));
  const std::vector<int> counts = args.lights.empty() ? std::vector<int>{} : parse_counts(args.lights);
  std::vector<Scene> scenes;
  if (counts.empty()) scenes.push_back(scene);
  for (int count : counts) scenes.push_back(with_many_lights(scene, gbuffer, count));
  if (!counts.empty()) {
    // The unculled kernel's pixel-lights/s at 16 lights: what culling's effective rate is held to.
    const Scene sixteen = with_many_lights(scene, gbuffer, kUnculledRateLights);
    std::cout << "  lights     " << kUnculledRateLights << " (the unculled rate)\n";
    bench.unculled(sixteen, {mean_lights_reaching(sixteen, gbuffer, 97), 0.0}, nullptr);
  }
  for (const Scene& lit : scenes) {
    const auto start = Clock::now();
    const Reach reach{mean_lights_reaching(lit, gbuffer, 97),
                      mean_lights_reaching_tiles(lit, gbuffer, kTileSize, list_rows)};
    std::cout << "  lights     " << lit.lights.size() << ": a shaded pixel is reached by " << reach.pixel
              << " on average, one of its tile's pixels by " << reach.tile << "; reference rows..." << std::flush;
    const ReferenceRows reference(lit, gbuffer);
    std::cout << " every " << reference.step << "\n";
    bench.tiled(lit, reach, reference, args.peer_schedules);
    bench.unculled(lit, reach, &reference);
    std::cout << "    (" << static_cast<int>(elapsed_ms(start) / 1000) << " s)\n";
  }
  std::cout << "\n" << many_lights_table(bench.results());
  if (!args.json_file.empty()) write_text_file(args.json_file, many_lights_json(machine, bench.results()));
  if (!args.report_dir.empty()) {
    write_many_lights_report(args.report_dir, machine, bench.results());
    std::cout << "  wrote      " << args.report_dir << "/report.md, results.json, frame_ms_vs_lights.svg\n";
  }
}

}  // namespace phongcl::cli
