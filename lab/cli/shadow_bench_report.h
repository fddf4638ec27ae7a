#pragma once
// What `phongcl bench --shadows` measured, and its tables.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/bench_arguments.h"

namespace phongcl::cli {

struct ShadowTracerResult {
  std::string name;
  double build_ms = 0.0;       // its BVH, on the host
  double trace_ms = 0.0;       // median over the runs
  double disagreement = 0.0;   // fraction of the rays decided otherwise than the OpenCL traversal
  double mrays_per_s = 0.0;
};

struct ShadowRaysResult {
  std::string device, embree;  // descriptions (embree: "SKIP: ..." when absent)
  std::size_t triangles = 0, rays = 0;
  int bvh_depth = 0;
  double mesh_read_ms = 0.0;  // the PLY through Assimp, flattened into world space
  double bvh_build_ms = 0.0;
  std::vector<ShadowTracerResult> tracers;  // opencl first
};

// The same rays through every tracer (bench_shadow_rays.cpp); mesh files go to `scratch`.
ShadowRaysResult run_shadow_rays_bench(const BenchArguments& args, const std::filesystem::path& scratch);

std::string shadow_rays_table(const ShadowRaysResult& result);  // Markdown, with rays/s against Embree's packets

}  // namespace phongcl::cli
