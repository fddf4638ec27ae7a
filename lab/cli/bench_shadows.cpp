// phongcl bench --shadows: shadows' error against run time, and the OpenCL traversal against Embree
// on the same rays.
#include <iostream>

#include "cli/bench_arguments.h"
#include "cli/shadow_bench_report.h"
#include "report/report_files.h"
#include "report/scratch_directory.h"

namespace phongcl::cli {

void run_shadows_bench(const BenchArguments& args) {
  if (!args.report_dir.empty()) create_report_directory(args.report_dir);
  const ScratchDirectory scratch("phongcl-bench-shadows");
  std::cout << "phongcl bench --shadows\n";
  const ShadowRaysResult rays = run_shadow_rays_bench(args, scratch.path());
  std::cout << "\nShadow rays: " << rays.rays << " rays on " << rays.triangles << " triangles; " << rays.device << "; "
            << rays.embree << "\n\n" << shadow_rays_table(rays);
}

}  // namespace phongcl::cli
