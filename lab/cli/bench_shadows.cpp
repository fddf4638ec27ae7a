// phongcl bench --shadows: shadows' error against run time, and the OpenCL traversal against Embree
// on the same rays.
#include <iostream>
#include <unistd.h>

#include "cli/bench_arguments.h"
#include "cli/shadow_bench_report.h"
#include "report/report_files.h"

namespace phongcl::cli {

void run_shadows_bench(const BenchArguments& args) {
  namespace fs = std::filesystem;
  if (!args.report_dir.empty()) create_report_directory(args.report_dir);
  const fs::path scratch = fs::temp_directory_path() / ("phongcl-bench-shadows-" + std::to_string(::getpid()));
  fs::create_directories(scratch);
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  } cleanup{scratch};
  std::cout << "phongcl bench --shadows\n";
  const ShadowRaysResult rays = run_shadow_rays_bench(args, scratch);
  std::cout << "\nShadow rays: " << rays.rays << " rays on " << rays.triangles << " triangles; " << rays.device << "; "
            << rays.embree << "\n\n" << shadow_rays_table(rays);
}

}  // namespace phongcl::cli
