// phongcl bench --sequence: a shot of the bench scene with an orbiting camera, shaded (a) by shade's
// sequence mode, (b) by a loop of single-frame shade processes; against (c) the I/O floor, the
// same reads and writes through the same pipeline with OpenEXR on every core and no shading, (d)
// the same reads and writes one frame at a time (what a single-frame shade cannot beat), and (e)
// oiiotool copying each G-buffer to an image of the output's size. Every mode runs as its own
// process (wall clock including start-up; peak RSS from wait4), all in one run, per compression;
// the figures are each mode's fastest of --rounds rounds.
#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli/bench_arguments.h"
#include "cli/child_process.h"
#include "common/atomic_file.h"
#include "exr/exr_channels.h"
#include "gbuffer/layouts.h"
#include "peers/machine_limits.h"
#include "raycast/raycast.h"
#include "report/scratch_directory.h"
#include "scene/json_reader.h"
#include "sequence/frame_pattern.h"
#include "sequence/frame_pipeline.h"

namespace phongcl::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kOrbitDegreesPerFrame = 0.5;
// The I/O modes write these many distinct shaded frames in turn: real image content (its
// compression costs what the shaded outputs' does) without holding the whole shot in memory.
constexpr int kPreloadedImages = 3;

struct ModeResult {
  std::string mode, compression;
  int frames = 0, width = 0, height = 0;
  double seconds = 0.0, read_s = 0.0, shade_s = 0.0, write_s = 0.0, peak_rss_mb = 0.0;
  double fps() const { return seconds > 0 ? frames / seconds : 0.0; }
};

// Seconds of `stage` in a summary line ("read 1.23 s" or "read 812.4 ms"); 0 when absent.
double stage_seconds(const std::string& line, const std::string& stage) {
  std::smatch match;
  if (!std::regex_search(line, match, std::regex("\\b" + stage + " ([0-9.]+) (ms|s)\\b"))) return 0.0;
  return std::stod(match[1].str()) / (match[2].str() == "ms" ? 1000.0 : 1.0);
}
std::string line_starting(const std::string& output, const std::string& start) {
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind(start, 0) == 0) return line;
  return "";
}
// Adds a shade run's read, shading and write seconds from its summary ("stages" in sequence mode,
// "time" for one frame).
void add_split(const std::string& output, ModeResult& result) {
  std::string line = line_starting(output, "  stages     ");
  if (line.empty()) line = line_starting(output, "  time       ");
  result.read_s += stage_seconds(line, "read");
  result.shade_s += stage_seconds(line, "pack") + stage_seconds(line, "upload") + stage_seconds(line, "kernel") +
                    stage_seconds(line, "download");
  result.write_s += stage_seconds(line, "write");
}

void check(const ChildRun& run, const std::string& what, const fs::path& log) {
  if (run.exit_code != 0)
    throw std::runtime_error("bench --sequence: " + what + " failed (exit " + std::to_string(run.exit_code) + "); see " +
                             log.string() + (run.output.empty() ? "" : ": " + run.output.substr(0, 300)));
}

// The shot: frame f's scene has the camera orbited by f * kOrbitDegreesPerFrame about its look-at
// point; its G-buffer is ray cast and written once per compression. Two frames at a time.
void generate_shot(const fs::path& scene_file, const fs::path& dir, int frames, const std::vector<ExrCompression>& compressions) {
  std::ifstream in(scene_file);
  const nlohmann::json base = nlohmann::json::parse(in);
  std::atomic<int> next{1};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    for (int frame; (frame = next++) <= frames;) {
      try {
        nlohmann::json scene = base;
        scene.erase("gbuffer");
        auto& camera = scene.at("camera");
        const double angle = frame * kOrbitDegreesPerFrame * M_PI / 180.0;
        const double ex = camera["eye"][0].get<double>() - camera["look_at"][0].get<double>();
        const double ez = camera["eye"][2].get<double>() - camera["look_at"][2].get<double>();
        camera["eye"][0] = camera["look_at"][0].get<double>() + ex * std::cos(angle) - ez * std::sin(angle);
        camera["eye"][2] = camera["look_at"][2].get<double>() + ex * std::sin(angle) + ez * std::cos(angle);
        const fs::path frame_scene = FramePattern((dir / "s.####.json").string()).path(frame);
        std::ofstream(frame_scene) << scene.dump(2);
        const GBuffer gbuffer = generate_gbuffer(load_scene(frame_scene));
        for (const ExrCompression compression : compressions)
          write_gbuffer(gbuffer, FramePattern((dir / ("g." + std::string(exr::compression_name(compression)) + ".####.exr")).string()).path(frame),
                        ExrPixelType::float32, compression);
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        failure = std::current_exception();
      }
    }
  };
  std::thread second(worker);
  worker();
  second.join();
  if (failure) std::rethrow_exception(failure);
}

struct Shot {
  fs::path dir;
  int frames = 0;
  std::string compression;
  fs::path path(const std::string& prefix, int frame) const { return pattern(prefix).path(frame); }
  FramePattern pattern(const std::string& prefix) const {
    return FramePattern((dir / (prefix + "." + compression + ".####.exr")).string());
  }
  std::vector<int> frame_list() const {
    std::vector<int> list;
    for (int frame = 1; frame <= frames; ++frame) list.push_back(frame);
    return list;
  }
};

ModeResult sequence_mode(const Shot& shot, const std::string& exe, const fs::path& log) {
  ModeResult result{"sequence", shot.compression, shot.frames};
  const ChildRun run = run_program({exe, "shade", "--scene", (shot.dir / "s.####.json").string(), "--gbuffer",
                                    shot.pattern("g").text(), "--frames", "1-" + std::to_string(shot.frames), "--out",
                                    shot.pattern("sequence").text(), "--overwrite"},
                                   log);
  check(run, "shade (sequence mode)", log);
  result.seconds = run.seconds;
  result.peak_rss_mb = run.peak_rss_mb;
  add_split(run.output, result);
  return result;
}

// single_thread: OpenEXR on the calling thread only, as shade ran before it had a thread pool.
ModeResult processes_mode(const Shot& shot, const std::string& exe, const fs::path& log, bool single_thread) {
  ModeResult result{single_thread ? "processes-1-thread" : "processes", shot.compression, shot.frames};
  for (const int frame : shot.frame_list()) {
    std::vector<std::string> argv{exe, "shade", "--scene", FramePattern((shot.dir / "s.####.json").string()).path(frame).string(),
                                  "--gbuffer", shot.path("g", frame).string(), "--out", shot.path("process", frame).string()};
    if (single_thread) argv.insert(argv.end(), {"--threads", "1"});
    const ChildRun run = run_program(argv, log);
    check(run, "shade (frame " + std::to_string(frame) + ")", log);
    result.seconds += run.seconds;
    result.peak_rss_mb = std::max(result.peak_rss_mb, run.peak_rss_mb);
    add_split(run.output, result);
  }
  return result;
}

ModeResult oiiotool_mode(const Shot& shot, const fs::path& log) {
  ModeResult result{"oiiotool", shot.compression, shot.frames};
  for (const int frame : shot.frame_list()) {
    const ChildRun run = run_program({"oiiotool", shot.path("g", frame).string(), "--ch", "R=P.X,G=P.Y,B=P.Z,A=N.X", "-d",
                                      "float", "--compression", shot.compression, "-o", shot.path("oiiotool", frame).string()},
                                     log);
    check(run, "oiiotool (frame " + std::to_string(frame) + ")", log);
    result.seconds += run.seconds;
    result.peak_rss_mb = std::max(result.peak_rss_mb, run.peak_rss_mb);
  }
  return result;
}

// OpenEXR alone, in a forked child (so its peak RSS is its own): reads every G-buffer as shade
// does and writes shaded images of the output's size. pipelined: through run_frame_pipeline on
// every core; otherwise one frame after another, as one single-frame shade does its I/O.
ModeResult io_mode(const Shot& shot, bool pipelined) {
  ModeResult result{pipelined ? "io-floor" : "io-single", shot.compression, shot.frames};
  const ChildRun run = run_forked([&] {
    std::vector<Image> images;
    for (int i = 1; i <= std::min(kPreloadedImages, shot.frames); ++i) images.push_back(read_exr(shot.path("sequence", i)));
    exr::set_exr_threads(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
    const ExrCompression compression = exr::parse_compression(shot.compression);
    FrameStages stages;
    stages.read = [&](FrameWork& work) { work.gbuffer = read_gbuffer(shot.path("g", work.frame), ReadOptions{}).gbuffer; };
    stages.shade = [&](FrameWork& work) { work.image = images[static_cast<std::size_t>(work.frame) % images.size()]; };
    stages.write = [&](FrameWork& work) {
      write_exr(work.image, shot.path("floor", work.frame), ExrWriteOptions{.compression = compression});
    };
    FrameTimes totals;
    const auto start = Clock::now();
    if (pipelined) {
      run_frame_pipeline(shot.frame_list(), stages, {}, [&](const FrameWork& work) {
        if (work.error) std::rethrow_exception(work.error);
        totals += work.times;
      });
    } else {
      for (const int frame : shot.frame_list()) {
        FrameWork work;
        work.frame = frame;
        auto stage_start = Clock::now();
        stages.read(work);
        totals.read_ms += std::chrono::duration<double, std::milli>(Clock::now() - stage_start).count();
        stages.shade(work);
        stage_start = Clock::now();
        stages.write(work);
        totals.write_ms += std::chrono::duration<double, std::milli>(Clock::now() - stage_start).count();
      }
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return std::to_string(seconds) + " " + std::to_string(totals.read_ms / 1000.0) + " " + std::to_string(totals.write_ms / 1000.0);
  });
  if (run.exit_code != 0) throw std::runtime_error("bench --sequence: " + result.mode + " failed: " + run.output);
  std::istringstream(run.output) >> result.seconds >> result.read_s >> result.write_s;
  result.peak_rss_mb = run.peak_rss_mb;
  return result;
}

bool have_program(const std::string& name) {
  return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

const ModeResult* find(const std::vector<ModeResult>& results, const std::string& mode, const std::string& compression) {
  for (const auto& result : results)
    if (result.mode == mode && result.compression == compression) return &result;
  return nullptr;
}

void print_table(const std::vector<ModeResult>& results) {
  std::printf("  %-18s %-5s %7s %9s %8s %8s %8s %9s\n", "mode", "comp", "frames", "frames/s", "read s", "shade s",
              "write s", "peak MB");
  for (const auto& r : results)
    std::printf("  %-18s %-5s %7d %9.2f %8.2f %8.2f %8.2f %9.0f\n", r.mode.c_str(), r.compression.c_str(), r.frames,
                r.fps(), r.read_s, r.shade_s, r.write_s, r.peak_rss_mb);
}

void print_targets(const std::vector<ModeResult>& results, const std::string& compression) {
  const ModeResult* sequence = find(results, "sequence", compression);
  const ModeResult* processes = find(results, "processes", compression);
  const ModeResult* floor = find(results, "io-floor", compression);
  const ModeResult* single_io = find(results, "io-single", compression);
  if (!sequence || !processes || !floor || !single_io) return;
  const double of_floor = sequence->fps() / floor->fps();
  const double over_processes = sequence->fps() / processes->fps();
  const double single_ratio = (processes->seconds / processes->frames) / (single_io->seconds / single_io->frames);
  std::printf("  %s: sequence = %.0f%% of the I/O floor's frames/s (target >= 85%%): %s\n", compression.c_str(),
              100.0 * of_floor, of_floor >= 0.85 ? "met" : "MISSED");
  std::printf("  %s: sequence = %.2fx the loop of processes (target >= 2x): %s\n", compression.c_str(), over_processes,
              over_processes >= 2.0 ? "met" : "MISSED");
  if (const ModeResult* single_thread = find(results, "processes-1-thread", compression))
    std::printf("  %s: sequence = %.2fx the loop of single-threaded processes (shade before its EXR thread pool)\n",
                compression.c_str(), sequence->fps() / single_thread->fps());
  std::printf("  %s: one shade process = %.2fx reading + writing one frame with OpenEXR (target <= 1.3x): %s\n",
              compression.c_str(), single_ratio, single_ratio <= 1.3 ? "met" : "MISSED");
}

nlohmann::json to_json(const std::vector<ModeResult>& results, const std::string& load_before, const std::string& load_after) {
  struct utsname system = {};
  ::uname(&system);
  nlohmann::json json;
  json["machine"] = {{"cpu", cpu_model_name()},
                     {"cores", std::thread::hardware_concurrency()},
                     {"kernel", std::string(system.sysname) + " " + system.release},
                     {"loadavg_before", load_before},
                     {"loadavg_after", load_after}};
  json["results"] = nlohmann::json::array();
  for (const auto& r : results)
    json["results"].push_back({{"mode", r.mode}, {"frames", r.frames}, {"width", r.width}, {"height", r.height},
                               {"compression", r.compression}, {"fps", r.fps()}, {"seconds", r.seconds},
                               {"read_s", r.read_s}, {"shade_s", r.shade_s}, {"write_s", r.write_s},
                               {"peak_rss_mb", r.peak_rss_mb}});
  return json;
}

}  // namespace

void run_sequence_bench(const BenchArguments& args) {
  std::vector<ExrCompression> compressions;
  std::stringstream list(args.compressions);
  for (std::string name; std::getline(list, name, ',');) compressions.push_back(exr::parse_compression(name));
  // The product's command line, which phongcl-lab is installed and built beside.
  const std::string exe = (fs::read_symlink("/proc/self/exe").parent_path() / "phongcl").string();
  const ScratchDirectory scratch("phongcl-bench-sequence");
  const fs::path& dir = scratch.path();
  const fs::path log = dir / "errors.log";

  std::cout << "phongcl bench --sequence: " << args.sequence_frames << " frames of " << args.inputs.scene_file
            << ", camera orbiting " << kOrbitDegreesPerFrame << " degrees a frame; best of " << args.rounds
            << " rounds\n";
  generate_shot(args.inputs.scene_file, dir, args.sequence_frames, compressions);
  const GBuffer first = read_gbuffer(FramePattern((dir / ("g." + std::string(exr::compression_name(compressions.front())) + ".####.exr")).string()).path(1));
  const std::string load_before = load_average();
  std::cout << "  image      " << first.width << " x " << first.height << "; load average before " << load_before << "\n";

  const bool oiiotool = have_program("oiiotool");
  // Round-robin: every mode once per round, and each mode's fastest round kept, so a burst of load
  // from other work on the machine hits one round of one mode rather than a whole mode.
  std::vector<ModeResult> results;
  for (int round = 1; round <= args.rounds; ++round) {
    for (const ExrCompression compression : compressions) {
      const Shot shot{dir, args.sequence_frames, exr::compression_name(compression)};
      // Sequence first: the I/O modes write its shaded frames.
      std::vector<ModeResult> measured{sequence_mode(shot, exe, log), io_mode(shot, true),
                                       processes_mode(shot, exe, log, false), io_mode(shot, false),
                                       processes_mode(shot, exe, log, true)};
      if (oiiotool) measured.push_back(oiiotool_mode(shot, log));
      for (const ModeResult& result : measured) {
        const auto best = std::find_if(results.begin(), results.end(), [&](const ModeResult& kept) {
          return kept.mode == result.mode && kept.compression == result.compression;
        });
        if (best == results.end()) {
          results.push_back(result);
        } else if (result.seconds < best->seconds) {
          *best = result;
        }
      }
      std::cout << "  measured   round " << round << ", " << shot.compression << " (load average " << load_average()
                << ")\n";
      std::cout.flush();
    }
  }
  for (auto& result : results) {
    result.width = first.width;
    result.height = first.height;
  }
  const std::string load_after = load_average();
  print_table(results);
  for (const ExrCompression compression : compressions) print_targets(results, exr::compression_name(compression));
  if (!oiiotool) std::cout << "  note       oiiotool not installed: its mode was skipped (scripts/setup.sh bench)\n";
  std::cout << "  load       " << load_before << " before, " << load_after << " after\n";
  if (!args.json_file.empty()) {
    write_atomically(args.json_file, [&](const fs::path& temp) {
      std::ofstream out(temp);
      out << to_json(results, load_before, load_after).dump(2) << "\n";
      if (!out) throw std::runtime_error("cannot write " + args.json_file);
    });
    std::cout << "  wrote      " << args.json_file << "\n";
  }
}

}  // namespace phongcl::cli
