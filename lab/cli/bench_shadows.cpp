// phongcl bench --shadows: shadows' error against run time, soft shadows' against their rays, and
// the OpenCL traversal against Embree on the same rays.
#include <iostream>

#include "cli/bench_arguments.h"
#include "cli/shadow_bench_report.h"
#include "peers/machine_limits.h"
#include "report/report_files.h"
#include "report/scratch_directory.h"

namespace phongcl::cli {

void run_shadows_bench(const BenchArguments& args) {
  if (!args.report_dir.empty()) create_report_directory(args.report_dir);
  const ScratchDirectory scratch("phongcl-bench-shadows");
  ShadowBenchMachine machine{cpu_model_name(), load_average(), ""};
  std::cout << "phongcl bench --shadows (" << args.runs << " timed runs per variant after one warm-up; load "
            << machine.load_start << ")\n";
  const std::vector<ShadowSceneResult> scenes = run_shadow_error_bench(args, scratch.path());
  run_soft_shadow_bench(args);
  const ShadowRaysResult rays = run_shadow_rays_bench(args, scratch.path());
  std::cout << "\nShadow rays: " << rays.rays << " rays on " << rays.triangles << " triangles; " << rays.device << "; "
            << rays.embree << "\n\n" << shadow_rays_table(rays.tracers) << "\nTheir soft rays (spheres, 16 per pixel): "
            << rays.soft_rays << " rays\n\n" << shadow_rays_table(rays.soft_tracers);
  machine.load_end = load_average();
  std::cout << "  load       " << machine.load_end << " at the end\n";
  if (!args.report_dir.empty())
    std::cout << "\n  wrote      " << write_shadow_report(args.report_dir, machine, scenes, rays) << "\n";
}

}  // namespace phongcl::cli
