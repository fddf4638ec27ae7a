#pragma once
// Phong shading of a G-buffer on an OpenCL device: recipe, kernel build (cached), packing, launch.
#include <memory>
#include <string>
#include <vector>

#include "cl/program_cache.h"
#include "cl/reusable_buffer.h"
#include "image/image.h"
#include "shading/pack.h"
#include "shading/recipe.h"
#include "shading/tile_culling.h"

namespace phongcl {

// Milliseconds. pack: host packing into mapped device memory; upload: unmapping it; kernel:
// profiling events; download: mapping the result and copying it out. total: wall clock of all of
// it, build excluded (build_ms says what the build cost, 0 on a memory-cache hit).
struct ShadeTimings {
  double build_ms = 0.0, pack_ms = 0.0, upload_ms = 0.0, kernel_ms = 0.0, download_ms = 0.0, total_ms = 0.0;
};

// The three terms of L_o as images (RGB, alpha as in the combined image); their sum is the
// combined image up to float rounding. Filled only with ShadeOptions::write_terms.
struct TermImages {
  Image ambient, diffuse, specular;
};

struct ShadeResult {
  Image image;
  TermImages terms;
  Recipe recipe;
  std::string build_options;
  CacheOutcome cache = CacheOutcome::compiled;
  ShadeTimings timings;
  PixelCounts counts;
  CullingStats culling;  // with recipe.tiled; its time is also inside timings.kernel_ms
  std::size_t tiles = 0;
  std::vector<std::string> warnings;
};

class PhongShader {
 public:
  PhongShader(ComputeContext compute, ProgramCache& cache) : compute_(std::move(compute)), cache_(cache) {}

  // Checks material indices against the scene (InputError), builds or reuses the kernel the
  // recipe asks for, and shades every pixel. Frames larger than the device's largest allocation
  // are shaded in tiles of whole pixel ranges. Device buffers are kept for the next frame.
  ShadeResult shade(const Scene& scene, const GBuffer& gbuffer, const ShadeOptions& options);

  const ComputeContext& compute() const { return compute_; }

 private:
  ComputeContext compute_;
  ProgramCache& cache_;
  // ALLOC_HOST_PTR + map/unmap: on a CPU device packing writes straight into device memory.
  ReusableBuffer planes_{CL_MEM_READ_ONLY | CL_MEM_ALLOC_HOST_PTR};
  ReusableBuffer material_index_{CL_MEM_READ_ONLY | CL_MEM_ALLOC_HOST_PTR};
  ReusableBuffer output_{CL_MEM_WRITE_ONLY | CL_MEM_ALLOC_HOST_PTR};
  ReusableBuffer terms_{CL_MEM_WRITE_ONLY | CL_MEM_ALLOC_HOST_PTR};
  std::unique_ptr<TileCuller> culler_;  // built for culler_options_
  std::string culler_options_;
};

}  // namespace phongcl
