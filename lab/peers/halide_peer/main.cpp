// phongcl-halide-peer: the Halide peer of `phongcl bench --throughput`, in its own process because
// Halide 14's LLVM and PoCL's cannot share one. Reads the peers' packed input (peers/packed_file.h),
// JIT-compiles the pipeline for this machine, shades it once untimed and then `--runs` timed times
// (fewer, at least min(3, runs), where they would exceed about --budget-ms, as the benchmark does),
// writes the RGBA floats (4 per pixel) to --output and prints one JSON line to stdout:
//   {"schedule": ..., "target": ..., "compile_ms": ..., "threads": ..., "times_ms": [...], "cpu_ms_per_run": ...}
// Times are the wall clock of realize() on pre-packed input (like the C++ peers' shading loop);
// the JIT compile is reported, not timed.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "peers/packed_file.h"
#include "phong_pipeline.h"

namespace {

using namespace phongcl;
using namespace phongcl::halide_peer;
using Clock = std::chrono::steady_clock;

constexpr std::size_t kMinimumPixels = 64;

// CPU time of every thread of this process: unlike the wall clock, it does not count time the
// threads spent descheduled on a shared machine.
double cpu_ms() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto ms = [](const timeval& t) { return t.tv_sec * 1e3 + t.tv_usec * 1e-3; };
  return ms(usage.ru_utime) + ms(usage.ru_stime);
}

double ms_since(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

struct Arguments {
  std::string input, output, schedule = schedules().front().name;
  int runs = 10;
  double budget_ms = 1e30;
};

Arguments parse(int argc, char** argv) {
  Arguments args;
  for (int a = 1; a < argc; ++a) {
    const std::string flag = argv[a];
    if (flag == "--list-schedules") {
      for (const Schedule& s : schedules()) std::cout << s.name << ": " << s.description << "\n";
      std::exit(0);
    }
    if (a + 1 >= argc) throw std::invalid_argument("usage: phongcl-halide-peer --input F --output F [--runs N] [--budget-ms B] [--schedule S] | --list-schedules");
    const std::string value = argv[++a];
    if (flag == "--input") args.input = value;
    else if (flag == "--output") args.output = value;
    else if (flag == "--schedule") args.schedule = value;
    else if (flag == "--runs") args.runs = std::stoi(value);
    else if (flag == "--budget-ms") args.budget_ms = std::stod(value);
    else throw std::invalid_argument("unknown flag " + flag);
  }
  if (args.input.empty() || args.output.empty() || args.runs < 1) throw std::invalid_argument("--input, --output and --runs >= 1 are required");
  return args;
}

// Columns of a scene table as one (row, column) buffer with at least one row.
Halide::Buffer<float> table(const std::vector<const std::vector<float>*>& columns) {
  const int rows = static_cast<int>(std::max<std::size_t>(columns.front()->size(), 1));
  Halide::Buffer<float> buffer(rows, static_cast<int>(columns.size()));
  buffer.fill(0.0f);
  for (std::size_t c = 0; c < columns.size(); ++c) {
    for (std::size_t r = 0; r < columns[c]->size(); ++r) buffer(static_cast<int>(r), static_cast<int>(c)) = (*columns[c])[r];
  }
  return buffer;
}

template <typename T>
Halide::Buffer<T> plane(const AlignedVector<T>& v) {
  return Halide::Buffer<T>(const_cast<T*>(v.data()), static_cast<int>(v.size()));
}

int run(const Arguments& args) {
  PackedInputs packed = read_packed_inputs(args.input);
  PackedFrame& f = packed.frame;
  const PackedScene& s = packed.scene;
  // The schedules split the frame into vectors of up to kMinimumPixels: tiny frames get more padding.
  for (auto* plane : {&f.px, &f.py, &f.pz, &f.nx, &f.ny, &f.nz}) plane->resize(std::max(plane->size(), kMinimumPixels), 0.0f);
  f.material.resize(std::max(f.material.size(), kMinimumPixels), kPeerBackground);
  const int padded = static_cast<int>(f.px.size());

  PipelineInputs in;
  const Halide::Target target = Halide::get_jit_target_from_environment();
  const auto compile_start = Clock::now();
  Halide::Func rgba = phong_pipeline(in, args.schedule);
  rgba.compile_jit(target);
  const double compile_ms = ms_since(compile_start);

  in.px.set(plane(f.px)), in.py.set(plane(f.py)), in.pz.set(plane(f.pz));
  in.nx.set(plane(f.nx)), in.ny.set(plane(f.ny)), in.nz.set(plane(f.nz));
  in.material.set(plane(f.material));
  in.materials.set(table({&s.ambient_r, &s.ambient_g, &s.ambient_b, &s.kd_r, &s.kd_g, &s.kd_b, &s.ks_r, &s.ks_g, &s.ks_b, &s.shininess, &s.alpha}));
  in.point_lights.set(table({&s.point_x, &s.point_y, &s.point_z, &s.point_r, &s.point_g, &s.point_b}));
  in.directional_lights.set(table({&s.dir_x, &s.dir_y, &s.dir_z, &s.dir_r, &s.dir_g, &s.dir_b}));
  in.point_count.set(s.point_count());
  in.directional_count.set(s.directional_count());
  // Enough chunks per thread to balance, few enough to keep task overhead out; never past the frame.
  const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  in.chunk.set(std::max(padded / (16 * threads) / 64 * 64, static_cast<int>(kMinimumPixels)));

  // Every padded pixel is shaded (the padding is background); the first `pixels` are written out.
  Halide::Buffer<float> output(4, padded);
  rgba.realize(output);  // warm-up: first touch of the output, thread pool start
  std::vector<double> times;
  const double cpu_start = cpu_ms();
  int runs = args.runs;
  while (static_cast<int>(times.size()) < runs) {
    const auto start = Clock::now();
    rgba.realize(output);
    times.push_back(ms_since(start));
    if (times.size() == 1) runs = std::clamp(static_cast<int>(args.budget_ms / std::max(times[0], 1e-3)), std::min(3, args.runs), args.runs);
  }

  const double cpu_end = cpu_ms();
  std::ofstream out(args.output, std::ios::binary);
  out.write(reinterpret_cast<const char*>(output.data()), static_cast<std::streamsize>(f.pixels * 4 * sizeof(float)));
  if (!out.flush()) throw std::runtime_error(args.output + ": cannot write");
  const nlohmann::ordered_json result = {
      {"schedule", args.schedule}, {"target", target.to_string()}, {"compile_ms", compile_ms}, {"threads", threads},
      {"times_ms", times}, {"cpu_ms_per_run", (cpu_end - cpu_start) / static_cast<double>(times.size())}};
  std::cout << result.dump() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse(argc, argv));
  } catch (const Halide::CompileError& e) {
    std::cerr << "phongcl-halide-peer: Halide compile error: " << e.what() << "\n";
  } catch (const Halide::Error& e) {
    std::cerr << "phongcl-halide-peer: Halide error: " << e.what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "phongcl-halide-peer: " << e.what() << "\n";
  }
  return 1;
}
