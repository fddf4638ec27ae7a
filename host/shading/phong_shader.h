#pragma once
// Phong shading of a G-buffer on an OpenCL device: kernel build (cached), packing, launch and
// download, in tiles when a frame is larger than one device allocation. The one engine under
// phongcl::Relighter (include/phongcl/relighter.hpp, which `phongcl shade` uses) and the lab.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cl/program_cache.h"
#include "cl/reusable_buffer.h"
#include "image/image.h"
#include "shading/phong_launch.h"
#include "shading/pack.h"
#include "shading/recipe.h"
#include "shading/shade_stats.h"
#include "shading/shadow_culling.h"
#include "shading/shadow_inputs.h"
#include "shading/tile_culling.h"

namespace phongcl {

// A one-shot frame: the report, the images, and the recipe they were shaded with.
struct ShadeResult : ShadeReport {
  Image image;
  TermImages terms;  // filled only with ShadeOptions::write_terms
  Recipe recipe;
};

// Where a frame goes: RGBA floats, 4 per pixel, row-major; the term images' too, or null to leave
// out a recipe's terms.
struct FrameTargets {
  float* rgba = nullptr;
  float* ambient = nullptr;
  float* diffuse = nullptr;
  float* specular = nullptr;
  std::vector<float*> groups{};  // with light groups: one RGBA image per group, or empty to leave them out
};

class PhongShader {
 public:
  PhongShader(ComputeContext compute, ProgramCache& cache) : compute_(std::move(compute)), cache_(cache) {}

  // One frame from scratch: checks material indices against the scene (InputError), makes the
  // recipe, packs and shades every pixel into new images.
  ShadeResult shade(const Scene& scene, const GBuffer& gbuffer, const ShadeOptions& options);

  // Shades `gbuffer` lit by `scene` with `recipe` (materials already checked) into `targets`. What
  // the previous call left on the device is reused unless forgotten: the kernel when the build
  // options are the same, the light and material tables, and the packed G-buffer when the frame
  // fit one launch and was packed for the same eye, precision and planes.
  // `max_tile_pixels` > 0 caps the pixels per launch.
  ShadeReport shade_into(const Scene& scene, const GBuffer& gbuffer, const Recipe& recipe, const FrameTargets& targets,
                         std::size_t max_tile_pixels = 0);
  // The next shade_into packs the G-buffer again (another G-buffer: its shadows' geometry and depth
  // plane too) / uploads the tables again.
  void forget_gbuffer() {
    packed_.reset();
    shadows_.reset();
  }
  void forget_uniforms() { uniforms_.reset(); }

  const ComputeContext& compute() const { return compute_; }
  const ProgramCache& cache() const { return cache_; }

 private:
  // What the resident G-buffer was packed for, and what packing it found.
  struct PackedFor {
    glm::dvec3 eye;
    Precision precision;
    int planes;
    std::size_t stride;
    bool operator==(const PackedFor&) const = default;
  };
  struct PackedFrame {
    PackedFor key;
    PixelCounts counts;
    std::size_t flushed_to_zero = 0;
  };
  // What the resident shadow inputs were built for.
  struct ShadowsFor {
    glm::dvec3 eye;
    ShadowMode mode;
    int steps;
    double thickness;
    bool half;
    bool operator==(const ShadowsFor&) const = default;
  };
  struct ResidentShadows {
    ShadowsFor key;
    ShadowDevice device;
  };
  // What a frame's launches share: the tile stride, the device buffers, the culling grid.
  struct FrameSetup {
    std::size_t stride = 0;  // values per plane: pixels per launch, rounded up to the lanes
    PackTarget pack_target;
    const cl::Buffer& output;  // PHONGCL_OUTPUT_PLANES planes
    const cl::Buffer& terms;   // PHONGCL_TERM_PLANES planes with write_terms
    TileLayout tiles;
    TileCuller* culler = nullptr;  // with tiled culling
    TileLayout shadow_tiles;
    ShadowCuller* shadow_culler = nullptr;  // with geometry shadows culled per tile
    PackedFor packed_for;
    bool resident = false;  // one launch holds the frame: its packed G-buffer is kept
  };
  cl::Kernel& kernel_for(ShadeReport& report);
  TileCuller& culler_for(const std::string& build_options);
  ShadowCuller& shadow_culler_for(const std::string& build_options);
  // With shadows: their inputs, built unless kept.
  void prepare_shadows(const Scene& scene, const GBuffer& gbuffer, const Recipe& recipe, ShadeReport& report);
  // The frame's buffers and tables (uploaded unless kept), and whether the packed G-buffer is kept.
  FrameSetup prepare(const Scene& scene, const GBuffer& gbuffer, const Recipe& recipe, std::size_t max_tile_pixels,
                     ShadeReport& report);
  // Packs pixels [first, first + count) unless the kept G-buffer holds them; returns the values
  // half-storage flushed to zero.
  std::size_t pack_or_reuse(const FrameSetup& frame, const Scene& scene, const GBuffer& gbuffer, const Recipe& recipe,
                            std::size_t first, std::size_t count, std::size_t padded, ShadeReport& report);
  // Culls the launch's tiles (with tiled culling) and enqueues phong_shade over `padded` slots.
  cl::Event cull_and_launch(cl::Kernel& kernel, FrameSetup& frame, const Recipe& recipe, std::size_t first,
                            std::size_t padded, ShadeReport& report);
  // Copies the launch's output planes (and terms) into the targets' pixels [first, first + count).
  void download(const FrameSetup& frame, const GBuffer& gbuffer, const Recipe& recipe, std::size_t first,
                std::size_t count, const FrameTargets& targets, ShadeReport& report);

  ComputeContext compute_;
  ProgramCache& cache_;
  std::optional<cl::Kernel> kernel_;  // built for kernel_options_
  std::string kernel_options_;
  std::optional<DeviceUniforms> uniforms_;  // packed for uniforms_options_, uniforms_stride_ and uniforms_rays_
  std::string uniforms_options_;
  std::size_t uniforms_stride_ = 0;
  int uniforms_rays_ = 0;  // the default shadow rays the area lights' table was packed with
  int uniforms_environment_rays_ = 0;  // the environment's visibility rays its record was packed with
  std::optional<PackedFrame> packed_;  // the planes hold the whole frame, packed for this
  std::uint64_t packings_ = 0;         // the planes' packings so far: the last one's number (BoxesKey)
  std::optional<ResidentShadows> shadows_;
  cl::Buffer shadow_lights_;  // uploaded with the tables (ShadowCasters' lights; their words are in the scene block)
  std::size_t shadow_light_count_ = 0;
  // ALLOC_HOST_PTR + map/unmap: on a CPU device packing writes straight into device memory.
  ReusableBuffer planes_{CL_MEM_READ_ONLY | CL_MEM_ALLOC_HOST_PTR};
  ReusableBuffer material_index_{CL_MEM_READ_ONLY | CL_MEM_ALLOC_HOST_PTR};
  ReusableBuffer output_{CL_MEM_WRITE_ONLY | CL_MEM_ALLOC_HOST_PTR};
  ReusableBuffer terms_{CL_MEM_WRITE_ONLY | CL_MEM_ALLOC_HOST_PTR};
  std::vector<float> half_staging_;  // PackTarget::half_staging
  std::unique_ptr<TileCuller> culler_;  // built for culler_options_
  std::string culler_options_;
  std::unique_ptr<ShadowCuller> shadow_culler_;  // built for shadow_culler_options_
  std::string shadow_culler_options_;
};

}  // namespace phongcl
