// phongcl bench: registers the options both benchmarks share and picks one.
#include <memory>

#include "cli/bench_arguments.h"
#include "cli/lab_commands.h"

namespace phongcl::cli {

void add_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArguments>();
  CLI::App* command = app.add_subcommand("bench", "Measure every kernel variant: error against run time, or throughput");
  args->inputs.add_options(*command);
  command->add_option("--device", args->device, "OpenCL device: index or name (default: a GPU, else the CPU with most compute units; see phongcl devices)");
  command->add_option("--runs", args->runs, "Timed runs per measurement, after one warm-up (default 10)")
      ->check(CLI::Range(1, 1000000));
  command->add_option("--report", args->report_dir, "Directory for report.md, report.json and the chart");
  command->add_flag("--throughput", args->throughput, "Compare throughput with C++ peers and the machine's limits");
  command->add_flag("--many-lights", args->many_lights,
                    "Tiled light culling against the unculled kernel and a tiled C++ peer, many ranged lights");
  command->add_flag("--peer-schedules", args->peer_schedules,
                    "--many-lights: also time cpp-tiled at every schedule of a grid (tiles of 8, 16, 32; coarse boxes "
                    "of 4, 8, 16 tiles; 1, 4, 16 tiles per task) and report its best");
  command->add_option("--lights", args->lights,
                      "--throughput: light counts to sweep (e.g. 0,1,4,16,64,256); --many-lights: generated lights "
                      "replacing the scene's (e.g. 64,256,1024,4096,10000)");
  command->add_option("--sizes", args->sizes, "--throughput: image sizes to sweep (e.g. 256x256,1920x1080)");
  command->add_option("--json", args->json_file, "--throughput, --sequence, --many-lights: write the results as JSON");
  command->add_flag("--sequence", args->sequence,
                    "Shade a generated shot in sequence mode against single-frame processes, the EXR I/O floor and oiiotool");
  command->add_option("--sequence-frames", args->sequence_frames, "--sequence: frames in the shot (default 8)")
      ->check(CLI::Range(1, 10000));
  command->add_option("--rounds", args->rounds, "--sequence: rounds of every mode, the fastest kept (default 3)")
      ->check(CLI::Range(1, 100));
  command->add_option("--compressions", args->compressions, "--sequence: EXR compressions to measure (default zip,piz)");
  command->add_flag("--shadows", args->shadows,
                    "Shadows: screen-space marches against exact geometry shadows (error against run time), and the "
                    "BVH traversal against Embree on the same rays, and soft shadows' error against their rays");
  command->add_flag("--soft-shadows", args->soft_shadows,
                    "Soft shadows alone (a part of --shadows): area lights' error and time at 1 to 64 rays, geometry and screen space");
  command->add_option("--mesh-triangles", args->mesh_triangles, "--shadows: triangles of the mesh scene (default 128000)")
      ->check(CLI::Range(1000, 100000000));
  command->add_flag("--environment", args->environment,
                    "Environment light: its visibility's error and time at 1 to 64 rays per pixel against 4096, "
                    "geometry and screen space");
  command->add_flag("--display", args->display,
                    "Time the PNG/serve display transforms (built-in views, Blender's Filmic with looks) on the scene's "
                    "shaded frame against OpenColorIO's own processor");
  command->add_flag("--groups", args->groups,
                    "Time light groups: the scene at 1920x1080 under 4 groups of 4 point lights, against the same 16 "
                    "lights without groups (kernel and download apart)");
  command->callback([args] {
    if (args->throughput + args->many_lights + args->sequence + args->shadows + args->soft_shadows + args->display +
            args->groups + args->environment > 1)
      throw CLI::ValidationError(
          "--throughput, --sequence, --many-lights, --shadows, --soft-shadows, --environment, --display and --groups "
          "are separate benchmarks: pick one");
    if (args->peer_schedules && !args->many_lights)
      throw CLI::ValidationError("--peer-schedules is an option of --many-lights");
    if (args->groups) return run_groups_bench(*args);
    if (args->shadows) return run_shadows_bench(*args);
    if (args->soft_shadows) return run_soft_shadow_bench(*args);
    if (args->environment) return run_environment_bench(*args);
    if (args->sequence) return run_sequence_bench(*args);
    if (args->display) return run_display_bench(*args);
    if (args->many_lights) return run_many_lights_bench(*args);
    args->throughput ? run_throughput_bench(*args) : run_error_vs_time_bench(*args);
  });
}

}  // namespace phongcl::cli
