#include "peers/opencl_shadow_rays.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "cl/kernel_source.h"

namespace phongcl {
namespace {

constexpr int kRayPlanes = 7;

// OpenCL has no empty buffers: an empty table gets one zeroed element, which the counts never reach.
template <typename T>
cl::Buffer table_buffer(const cl::Context& context, const std::vector<T>& table) {
  std::vector<T> copy = table.empty() ? std::vector<T>(1, T{}) : table;
  return cl::Buffer(context, copy.begin(), copy.end(), true);
}

int device_lanes(const DeviceInfo& device, int lanes) {
  if (lanes == 0) {
    lanes = 1;
    while (lanes < 16 && static_cast<unsigned>(lanes * 2) <= device.preferred_float_width) lanes *= 2;
  }
  if (lanes < 1 || lanes > 16 || (lanes & (lanes - 1)) != 0)
    throw std::invalid_argument("shadow rays: lanes must be 1, 2, 4, 8 or 16, not " + std::to_string(lanes));
  return lanes;
}

}  // namespace

std::size_t ShadowRaySet::traced() const {
  return static_cast<std::size_t>(std::count_if(t_max.begin(), t_max.end(), [](float t) { return t > 0.0f; }));
}

OpenClShadowRays::OpenClShadowRays(const ComputeContext& compute, ProgramCache& cache, const DeviceGeometry& geometry,
                                   int lanes)
    : compute_(compute),
      lanes_(device_lanes(compute.device.info, lanes)),
      program_(cache.build(compute, load_kernel_source("shadow_rays.cl"),
                           "-cl-std=CL1.2 -DPHONGCL_LANES=" + std::to_string(lanes_)).program),
      nodes_(table_buffer(compute.context, geometry.nodes)),
      primitives_(table_buffer(compute.context, geometry.primitives)),
      planes_(table_buffer(compute.context, geometry.planes)),
      node_count_(static_cast<cl_uint>(geometry.nodes.size())),
      plane_count_(static_cast<cl_uint>(geometry.planes.size())) {}

ShadowRaySet OpenClShadowRays::make_rays(const PackedFrame& frame, const Scene& scene, const glm::dvec3& eye,
                                         float offset_scale) {
  const std::size_t stride = frame.px.size();
  if (stride % static_cast<std::size_t>(lanes_) != 0) throw std::invalid_argument("shadow rays: frame not padded to the lanes");
  std::vector<float> pixels;
  for (const auto* plane : {&frame.px, &frame.py, &frame.pz, &frame.nx, &frame.ny, &frame.nz})
    pixels.insert(pixels.end(), plane->begin(), plane->end());
  const cl::Buffer pixel_buffer(compute_.context, pixels.begin(), pixels.end(), true);
  const cl::Buffer material_buffer(compute_.context, frame.material.begin(), frame.material.end(), true);
  const cl::Buffer ray_buffer(compute_.context, CL_MEM_WRITE_ONLY, kRayPlanes * stride * sizeof(float));
  cl::KernelFunctor<cl::Buffer, cl::Buffer, cl_uint, cl_float, cl_float, cl_float, cl_int, cl_float, cl_float, cl::Buffer>
      make(program_, "make_shadow_rays");
  const float eye_extent = static_cast<float>(std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)}));

  ShadowRaySet set;
  set.size = stride * scene.lights.size();
  AlignedVector<float>* planes[kRayPlanes] = {&set.ox, &set.oy, &set.oz, &set.dx, &set.dy, &set.dz, &set.t_max};
  for (AlignedVector<float>* plane : planes) plane->resize(set.size);
  std::vector<float> rays(kRayPlanes * stride);
  for (std::size_t k = 0; k < scene.lights.size(); ++k) {
    const Light& light = scene.lights[k];
    const bool directional = light.type == LightType::directional;
    // Relative to the eye in double, as the shading kernel's tables are; a direction as l = -normalize(d).
    const glm::dvec3 where = directional ? -glm::normalize(light.direction) : light.position - eye;
    make(cl::EnqueueArgs(compute_.queue, cl::NDRange(stride / lanes_)), pixel_buffer, material_buffer,
         static_cast<cl_uint>(stride), static_cast<float>(where.x), static_cast<float>(where.y),
         static_cast<float>(where.z), directional ? 1 : 0, offset_scale, eye_extent, ray_buffer);
    compute_.queue.enqueueReadBuffer(ray_buffer, CL_TRUE, 0, rays.size() * sizeof(float), rays.data());
    for (int p = 0; p < kRayPlanes; ++p)
      std::copy_n(rays.begin() + p * stride, stride, planes[p]->begin() + k * stride);
  }
  return set;
}

std::vector<float> OpenClShadowRays::trace(const ShadowRaySet& rays, double* kernel_ms) {
  if (rays.size % static_cast<std::size_t>(lanes_) != 0) throw std::invalid_argument("shadow rays: set not padded to the lanes");
  std::vector<float> packed;
  packed.reserve(kRayPlanes * rays.size);
  for (const auto* plane : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz, &rays.t_max})
    packed.insert(packed.end(), plane->begin(), plane->end());
  const cl::Buffer ray_buffer(compute_.context, packed.begin(), packed.end(), true);
  const cl::Buffer blocked_buffer(compute_.context, CL_MEM_WRITE_ONLY, std::max<std::size_t>(rays.size, 1) * sizeof(float));
  std::vector<float> blocked(rays.size, 0.0f);
  if (rays.size == 0) return blocked;
  cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl_uint, cl::Buffer> trace(
      program_, "trace_shadow_rays");
  cl::Event done = trace(cl::EnqueueArgs(compute_.queue, cl::NDRange(rays.size / lanes_)), ray_buffer,
                         static_cast<cl_uint>(rays.size), nodes_, node_count_, primitives_, planes_, plane_count_,
                         blocked_buffer);
  compute_.queue.enqueueReadBuffer(blocked_buffer, CL_TRUE, 0, blocked.size() * sizeof(float), blocked.data());
  if (kernel_ms) *kernel_ms = event_milliseconds(done);
  return blocked;
}

}  // namespace phongcl
