// phongcl bench --shadows, the ray tracers' part: the same shadow rays of a mesh scene (a trefoil
// knot of at least --mesh-triangles triangles over a ground, every light casting shadows) traced by
// the OpenCL traversal (kernels/bvh.h) and by Embree 3 on every core, in rays per second.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <omp.h>

#include "cl/compute_context.h"
#include "cl/device.h"
#include "cli/bench_arguments.h"
#include "cli/shadow_bench_report.h"
#include "geometry/device_geometry.h"
#include "geometry/scene_bvh.h"
#include "peers/knot_mesh.h"
#include "peers/machine_limits.h"
#include "peers/opencl_shadow_rays.h"
#include "peers/packed_frame.h"
#include "raycast/raycast.h"
#include "report/elapsed.h"
#include "report/statistics.h"
#include "common/writable_directory.h"
#ifdef PHONGCL_HAVE_EMBREE
#include "embree/embree_peer.h"
#endif

namespace phongcl::cli {

namespace {

using Clock = std::chrono::steady_clock;

// One untimed run, then `runs` timed; the median.
template <typename Run>
double median_of_runs(int runs, Run run) {
  run();
  std::vector<double> times;
  for (int r = 0; r < runs; ++r) times.push_back(run());
  return median(times);
}

double disagreement(const std::vector<float>& a, const std::vector<float>& b, const ShadowRaySet& rays) {
  std::size_t differ = 0;
  for (std::size_t i = 0; i < rays.size; ++i) differ += rays.t_max[i] > 0.0f && a[i] != b[i];
  return static_cast<double>(differ) / static_cast<double>(std::max<std::size_t>(rays.traced(), 1));
}

}  // namespace

// A knot of at least `triangles` triangles: rings of 64 sides, as many rings as it takes.
Scene mesh_scene(const std::filesystem::path& directory, int triangles, int lights, int width, int height) {
  constexpr int kSides = 64;
  const int segments = std::max(3, (triangles + 2 * kSides - 1) / (2 * kSides));
  Scene scene = knot_scene(directory, segments, kSides, lights);
  scene.camera.width = width;
  scene.camera.height = height;
  return scene;
}

namespace {

// The soft rays: knot_scene's point lights as spheres of this radius, this many rays per pixel (the
// default --shadow-rays).
constexpr float kSoftRadius = 0.25f;
constexpr int kSoftRays = 16;

#ifdef PHONGCL_HAVE_EMBREE
using EmbreeTracer = EmbreeShadowPeer;
#else
struct EmbreeTracer {};  // none: the OpenCL traversal alone
#endif

// One set of rays through the OpenCL traversal and (with Embree) both of Embree's APIs, each the
// median of `runs` after a warm-up, with rays per second.
std::vector<ShadowTracerResult> trace_each(OpenClShadowRays& tracer, const ShadowRaySet& rays, double bvh_build_ms,
                                           int runs, [[maybe_unused]] const EmbreeTracer& embree) {
  std::vector<ShadowTracerResult> tracers;
  std::vector<float> ours;
  const double ours_ms = median_of_runs(runs, [&] {
    double ms = 0.0;
    ours = tracer.trace(rays, &ms);
    return ms;
  });
  tracers.push_back({"opencl (" + std::to_string(tracer.lanes()) + " rays per work-item)", bvh_build_ms, ours_ms, 0.0});
#ifdef PHONGCL_HAVE_EMBREE
  for (EmbreeApi api : {EmbreeApi::packet16, EmbreeApi::single}) {
    std::vector<float> theirs;
    const double ms = median_of_runs(runs, [&] {
      double run_ms = 0.0;
      theirs = embree.trace(rays, api, &run_ms);
      return run_ms;
    });
    tracers.push_back({std::string("embree ") + to_string(api), embree.build_milliseconds(), ms,
                       disagreement(ours, theirs, rays)});
  }
#endif
  const auto traced = static_cast<double>(rays.traced());
  for (ShadowTracerResult& result : tracers) result.mrays_per_s = traced / (result.trace_ms * 1e-3) / 1e6;
  return tracers;
}

}  // namespace

ShadowRaysResult run_shadow_rays_bench(const BenchArguments& args, const std::filesystem::path& scratch) {
  ShadowRaysResult result;
  const Scene scene = mesh_scene(scratch, args.mesh_triangles, 4, 1280, 720);
  std::cout << "  rays       the same shadow rays, OpenCL against Embree: a knot of >= " << args.mesh_triangles
            << " triangles, 4 point lights, " << scene.camera.width << "x" << scene.camera.height
            << "; then their soft rays as spheres of radius " << kSoftRadius << ", " << kSoftRays << " per pixel\n";
  const GBuffer gbuffer = generate_gbuffer(scene);
  auto start = Clock::now();
  SceneShapes shapes = flatten_objects(scene.objects);
  result.mesh_read_ms = elapsed_ms(start);
  start = Clock::now();
  const SceneBvh bvh = build_scene_bvh(std::move(shapes), PHONGCL_BVH_MAX_DEPTH);
  result.triangles = bvh.shapes.triangles.size();
  result.bvh_build_ms = elapsed_ms(start);
  result.bvh_depth = bvh.bvh.depth;
  const glm::dvec3 eye = scene.camera.eye;
  ProgramCache cache(ProgramCache::default_directory());
  const ComputeContext compute = make_compute_context(pick_device(args.device));
  result.device = describe(compute.device.info);
  OpenClShadowRays tracer(compute, cache, pack_device_geometry(bvh, eye));
  tracer.set_frame(pack_frame(gbuffer, scene), gbuffer.width, gbuffer.height, scene, eye, PHONGCL_SHADOW_OFFSET_FLOAT);
#ifdef PHONGCL_HAVE_EMBREE
  const EmbreeTracer embree(bvh.shapes, eye);
  result.embree = embree.describe();
#else
  const EmbreeTracer embree;
  result.embree = "SKIP: Embree not installed (scripts/setup.sh embree)";
#endif
  const ShadowRaySet rays = tracer.make_rays();
  result.rays = rays.traced();
  result.tracers = trace_each(tracer, rays, result.bvh_build_ms, args.runs, embree);
  const ShadowRaySet soft = tracer.make_soft_rays(kSoftRadius, kSoftRays);
  result.soft_rays = soft.traced();
  result.soft_tracers = trace_each(tracer, soft, result.bvh_build_ms, args.runs, embree);
  std::cout << "    mesh read " << result.mesh_read_ms << " ms, BVH " << result.bvh_build_ms << " ms (depth "
            << result.bvh_depth << "); " << result.rays << " rays, " << result.soft_rays << " soft rays\n";
  return result;
}

}  // namespace phongcl::cli
