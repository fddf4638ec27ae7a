#pragma once
// What `phongcl bench --shadows` measured, and its tables.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/bench_arguments.h"
#include "scene/scene.h"

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
  std::size_t soft_rays = 0;                 // the same lights' soft rays (spheres, 16 per pixel)
  std::vector<ShadowTracerResult> soft_tracers;
};

// One way of making shadows on one scene, timed and compared with exact geometry shadows.
struct ShadowVariant {
  std::string label;        // "geometry", "off", "screen 32 steps, 6%"
  std::string mode;         // geometry, off, screen
  int steps = 0;            // screen
  std::string thickness;    // screen: "0.25" or "6%"
  double kernel_ms = 0.0;   // median over the runs, profiling events
  double mismatch = 0.0;    // fraction of shaded pixels whose shadows differ from geometry's (see shadow_error_bench)
  double mean_abs_error = 0.0;  // of the image against geometry's, over shaded pixels and R, G, B
};

// Every light's shadow rays per pixel without the shading around them (kernels/shadow_rays.cl's
// count_blocked_lights): every ray traversing the BVH (tile 0), or tested against its tile's
// candidates from tiled shadow culling (kernels/shadow_cull.cl).
struct ShadowCullingVariant {
  int tile = 0;                 // tile size in pixels; 0: every ray traverses
  double total_ms = 0.0;        // median: the culling passes and the rays' kernel
  double culling_ms = 0.0;      // median of the culling passes (and the host's prefix sums)
  double candidates_per_pair = 0.0, traversing_pairs = 0.0;
  std::size_t differing = 0;    // pixels whose count of blocked lights differs from the traversal's
};

struct ShadowSceneResult {
  std::string name;  // "default", "large (16 lights)", "knot mesh"
  int width = 0, height = 0, lights = 0;
  std::size_t shaded = 0;
  std::string geometry;  // how the exact shadows were made (ShadeReport::shadows)
  std::vector<ShadowVariant> variants;  // geometry, off, then screen by steps and thickness
  std::vector<ShadowCullingVariant> culling;  // traversal first, then tiles of 8, 16 and 32
};

// Exact, unshadowed and screen-space shadows (every light casting them) on --scene's scene,
// scenes/spotlights, scenes/large with 16 lights and a mesh scene (bench_shadow_error.cpp); mesh
// files go to `scratch`.
std::vector<ShadowSceneResult> run_shadow_error_bench(const BenchArguments& args, const std::filesystem::path& scratch);

// What else the machine was doing: /proc/loadavg before the first scene and after the rays.
struct ShadowBenchMachine {
  std::string cpu, load_start, load_end;
};

std::string shadow_error_table(const ShadowSceneResult& scene);  // Markdown, with the Pareto fronts
std::string shadow_culling_table(const ShadowSceneResult& scene);  // Markdown
// report.md, report.json and one chart per scene (error_<n>.svg) in `directory`; returns what it wrote.
std::string write_shadow_report(const std::filesystem::path& directory, const ShadowBenchMachine& machine,
                                const std::vector<ShadowSceneResult>& scenes, const ShadowRaysResult& rays);

// A knot of at least `triangles` triangles over a ground, `lights` point lights casting shadows.
Scene mesh_scene(const std::filesystem::path& directory, int triangles, int lights, int width, int height);

// The same rays through every tracer (bench_shadow_rays.cpp); mesh files go to `scratch`.
ShadowRaysResult run_shadow_rays_bench(const BenchArguments& args, const std::filesystem::path& scratch);

// Markdown, one tracer a row, with rays/s against the first's (the OpenCL traversal's).
std::string shadow_rays_table(const std::vector<ShadowTracerResult>& tracers);

}  // namespace phongcl::cli
