#include "peers/opencl_shadow_rays.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "cl/kernel_source.h"
#include "shading/tile_culling.h"

namespace phongcl {
namespace {

constexpr int kRayPlanes = 7;

int device_lanes(const DeviceInfo& device, int lanes) {
  if (lanes == 0) {
    lanes = 1;
    while (lanes < 16 && static_cast<unsigned>(lanes * 2) <= device.preferred_float_width) lanes *= 2;
  }
  if (lanes < 1 || lanes > 16 || (lanes & (lanes - 1)) != 0)
    throw std::invalid_argument("shadow rays: lanes must be 1, 2, 4, 8 or 16, not " + std::to_string(lanes));
  return lanes;
}

// Float arithmetic on float planes, as the shading kernel's precise variant (kernels/features.h).
std::string build_options(int lanes) {
  return "-cl-std=CL1.2 -DPHONGCL_LANES=" + std::to_string(lanes) + " -DPHONGCL_DOUBLE=0 -DPHONGCL_FAST=0 -DHALF_STORAGE=0";
}

cl::Program build(const ComputeContext& compute, ProgramCache& cache, const char* file, int lanes) {
  return cache.build(compute, load_kernel_source(file), build_options(lanes)).program;
}

}  // namespace

std::size_t ShadowRaySet::traced() const {
  return static_cast<std::size_t>(std::count_if(t_max.begin(), t_max.end(), [](float t) { return t > 0.0f; }));
}

OpenClShadowRays::OpenClShadowRays(const ComputeContext& compute, ProgramCache& cache, const DeviceGeometry& geometry,
                                   int lanes)
    : compute_(compute),
      lanes_(device_lanes(compute.device.info, lanes)),
      program_(build(compute, cache, "shadow_rays.cl", lanes_)),
      geometry_(upload_shadow_geometry(compute.context, geometry)),
      culler_(compute, cache, build_options(lanes_)) {}

void OpenClShadowRays::set_frame(const PackedFrame& frame, int width, int height, const Scene& scene,
                                 const glm::dvec3& eye, float offset_scale) {
  stride_ = frame.px.size();
  if (stride_ % static_cast<std::size_t>(lanes_) != 0) throw std::invalid_argument("shadow rays: frame not padded to the lanes");
  std::vector<float> pixels;
  for (const auto* plane : {&frame.px, &frame.py, &frame.pz, &frame.nx, &frame.ny, &frame.nz})
    pixels.insert(pixels.end(), plane->begin(), plane->end());
  pixels_ = cl::Buffer(compute_.context, pixels.begin(), pixels.end(), true);
  materials_ = cl::Buffer(compute_.context, frame.material.begin(), frame.material.end(), true);
  width_ = width;
  height_ = height;
  offset_scale_ = offset_scale;
  eye_extent_ = static_cast<float>(std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)}));
  // Relative to the eye in double, as the shading kernel's tables are; a direction as l = -normalize(d).
  std::vector<ShadowLight> lights;
  for (const Light& light : scene.lights) {
    const bool directional = light.type == LightType::directional;
    const glm::dvec3 where = directional ? -glm::normalize(light.direction) : light.position - eye;
    lights.push_back({{static_cast<float>(where.x), static_cast<float>(where.y), static_cast<float>(where.z)},
                      directional ? 1u : 0u, {0.0f, 0.0f, 0.0f}, 0.0f});
  }
  lights_ = table_buffer(compute_.context, lights);
  light_count_ = lights.size();
}

ShadowRaySet OpenClShadowRays::gather_frames(std::size_t frames,
                                             const std::function<void(std::size_t, const cl::Buffer&)>& launch) {
  const cl::Buffer ray_buffer(compute_.context, CL_MEM_WRITE_ONLY, kRayPlanes * stride_ * sizeof(float));
  ShadowRaySet set;
  set.size = stride_ * frames;
  AlignedVector<float>* planes[kRayPlanes] = {&set.ox, &set.oy, &set.oz, &set.dx, &set.dy, &set.dz, &set.t_max};
  for (AlignedVector<float>* plane : planes) plane->resize(set.size);
  std::vector<float> frame(kRayPlanes * stride_);
  for (std::size_t f = 0; f < frames; ++f) {
    launch(f, ray_buffer);
    compute_.queue.enqueueReadBuffer(ray_buffer, CL_TRUE, 0, frame.size() * sizeof(float), frame.data());
    for (int p = 0; p < kRayPlanes; ++p) std::copy_n(frame.begin() + p * stride_, stride_, planes[p]->begin() + f * stride_);
  }
  return set;
}

ShadowRaySet OpenClShadowRays::make_rays() {
  cl::KernelFunctor<cl::Buffer, cl::Buffer, cl_uint, cl::Buffer, cl_uint, cl_float, cl_float, cl::Buffer> make(
      program_, "make_shadow_rays");
  return gather_frames(light_count_, [&](std::size_t k, const cl::Buffer& rays) {
    make(cl::EnqueueArgs(compute_.queue, cl::NDRange(stride_ / lanes_)), pixels_, materials_, static_cast<cl_uint>(stride_),
         lights_, static_cast<cl_uint>(k), offset_scale_, eye_extent_, rays);
  });
}

ShadowRaySet OpenClShadowRays::make_soft_rays(float size, int rays) {
  cl::KernelFunctor<cl::Buffer, cl::Buffer, cl_uint, cl::Buffer, cl_uint, cl_float, cl_uint, cl_float, cl_float, cl::Buffer>
      make(program_, "make_soft_shadow_rays");
  const auto per_light = static_cast<std::size_t>(rays);
  return gather_frames(light_count_ * per_light, [&](std::size_t f, const cl::Buffer& buffer) {
    make(cl::EnqueueArgs(compute_.queue, cl::NDRange(stride_ / lanes_)), pixels_, materials_, static_cast<cl_uint>(stride_),
         lights_, static_cast<cl_uint>(f / per_light), size, static_cast<cl_uint>(f % per_light), offset_scale_, eye_extent_,
         buffer);
  });
}

std::vector<float> OpenClShadowRays::trace(const ShadowRaySet& rays, double* kernel_ms) {
  if (rays.size % static_cast<std::size_t>(lanes_) != 0) throw std::invalid_argument("shadow rays: set not padded to the lanes");
  std::vector<float> blocked(rays.size, 0.0f);
  if (rays.size == 0) return blocked;
  std::vector<float> packed;
  packed.reserve(kRayPlanes * rays.size);
  for (const auto* plane : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz, &rays.t_max})
    packed.insert(packed.end(), plane->begin(), plane->end());
  const cl::Buffer ray_buffer(compute_.context, packed.begin(), packed.end(), true);
  const cl::Buffer blocked_buffer(compute_.context, CL_MEM_WRITE_ONLY, rays.size * sizeof(float));
  cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl_uint, cl::Buffer> trace(
      program_, "trace_shadow_rays");
  cl::Event done = trace(cl::EnqueueArgs(compute_.queue, cl::NDRange(rays.size / lanes_)), ray_buffer,
                         static_cast<cl_uint>(rays.size), geometry_.nodes, geometry_.node_count, geometry_.primitives,
                         geometry_.planes, geometry_.plane_count, blocked_buffer);
  compute_.queue.enqueueReadBuffer(blocked_buffer, CL_TRUE, 0, blocked.size() * sizeof(float), blocked.data());
  if (kernel_ms) *kernel_ms = event_milliseconds(done);
  return blocked;
}

OpenClShadowRays::Counts OpenClShadowRays::count_blocked(Method method, int tile_size, const ScreenDepth* screen) {
  Counts counts;
  counts.blocked_lights.assign(stride_, 0.0f);
  if (stride_ == 0) return counts;
  if (method == Method::screen && screen == nullptr) throw std::invalid_argument("shadow rays: the screen march needs a depth plane");
  const TileLayout layout = tile_layout(width_, height_, tile_size, tile_size);
  ShadowLists lists{.grid = layout.grid, .tiles = static_cast<cl_uint>(layout.tile_count)};
  if (method == Method::culled) {
    const ShadowCullingStats stats = culler_.cull(pixels_, stride_, materials_, stride_, layout, geometry_, lights_,
                                                  light_count_, offset_scale_, eye_extent_);
    lists = culler_.lists();
    counts.culling_ms = stats.culling_ms;
    counts.candidates_per_pair = stats.candidates_per_pair();
    counts.traversing_pairs = static_cast<double>(stats.traversing) / static_cast<double>(std::max<std::size_t>(stats.pairs, 1));
  } else {  // the lists' buffers are never read
    lists.counts = lists.offsets = lists.candidates = cl::Buffer(compute_.context, CL_MEM_READ_ONLY, sizeof(cl_uint) * 2);
  }
  const cl::Buffer depth = screen ? table_buffer(compute_.context, screen->depth)
                                  : cl::Buffer(compute_.context, CL_MEM_READ_ONLY, sizeof(float));
  const ScreenMarch march = screen ? screen->march : ScreenMarch{};
  const cl::Buffer out(compute_.context, CL_MEM_WRITE_ONLY, stride_ * sizeof(float));
  cl::KernelFunctor<cl::Buffer, cl::Buffer, cl_uint, cl::Buffer, cl_uint, cl_float, cl_float, cl_int, TileGrid, cl_uint,
                    cl::Buffer, cl::Buffer, cl::Buffer, cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl_uint, cl::Buffer,
                    ScreenMarch, cl::Buffer>
      kernel(program_, "count_blocked_lights");
  cl::Event done = kernel(cl::EnqueueArgs(compute_.queue, cl::NDRange(stride_ / lanes_)), pixels_, materials_,
                          static_cast<cl_uint>(stride_), lights_, static_cast<cl_uint>(light_count_), offset_scale_,
                          eye_extent_, static_cast<cl_int>(method), lists.grid, lists.tiles, lists.counts, lists.offsets,
                          lists.candidates, geometry_.nodes, geometry_.node_count, geometry_.primitives, geometry_.planes,
                          geometry_.plane_count, depth, march, out);
  compute_.queue.enqueueReadBuffer(out, CL_TRUE, 0, stride_ * sizeof(float), counts.blocked_lights.data());
  counts.kernel_ms = event_milliseconds(done);
  return counts;
}

}  // namespace phongcl
