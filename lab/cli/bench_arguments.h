#pragma once
// `phongcl bench`: the error-against-run-time report (default) and, with --throughput, the
// throughput comparison against C++ peers and the machine's limits.
#include <string>

#include "cli/inputs.h"

namespace phongcl::cli {

struct BenchArguments {
  SceneInputs inputs;
  std::string device;
  int runs = 10;            // timed runs per variant, after one untimed warm-up
  std::string report_dir;   // report.md, report.json, chart
  bool throughput = false;
  bool many_lights = false;  // tiled culling against unculled and cpp-tiled
  bool peer_schedules = false;  // --many-lights: cpp-tiled at every schedule of a grid, its best reported
  std::string lights;       // --throughput: light counts to sweep, e.g. "0,1,4,16,64,256"
  std::string sizes;        // --throughput: image sizes to sweep, e.g. "256x256,1920x1080"
  std::string json_file;    // --throughput, --sequence: results as JSON
  bool sequence = false;
  bool display = false;      // the display transforms of 8-bit outputs against OpenColorIO's processor
  int sequence_frames = 8;   // --sequence: frames in the shot
  int rounds = 3;            // --sequence: rounds of every mode; each mode's fastest is kept
  std::string compressions = "zip,piz";  // --sequence: G-buffer and output compressions
  bool shadows = false;
  bool soft_shadows = false;  // the soft-shadow part of --shadows alone
  bool environment = false;   // the environment light's visibility: error against rays and time
  bool groups = false;       // light groups' cost: 4 groups of 4 lights against the same 16 ungrouped
  int mesh_triangles = 128000;  // --shadows: the mesh scene's triangles (at least)
};

void run_error_vs_time_bench(const BenchArguments& args);  // bench_error_vs_time.cpp
void run_throughput_bench(const BenchArguments& args);     // bench_throughput.cpp
void run_many_lights_bench(const BenchArguments& args);    // bench_many_lights.cpp
void run_sequence_bench(const BenchArguments& args);       // bench_sequence.cpp
void run_shadows_bench(const BenchArguments& args);        // bench_shadows.cpp
void run_soft_shadow_bench(const BenchArguments& args);    // bench_soft_shadows.cpp
void run_environment_bench(const BenchArguments& args);    // bench_environment.cpp
void run_display_bench(const BenchArguments& args);        // bench_display.cpp
void run_groups_bench(const BenchArguments& args);         // bench_groups.cpp

}  // namespace phongcl::cli
