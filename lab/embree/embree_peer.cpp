#include "embree/embree_peer.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <omp.h>
#include <stdexcept>

#include <embree3/rtcore.h>

namespace phongcl {

struct EmbreeShadowPeer::Handles {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

namespace {

using Clock = std::chrono::steady_clock;

double since_ms(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

void check(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree: ") + what + " failed (error " + std::to_string(error) + ")");
}

}  // namespace

const char* to_string(EmbreeApi api) { return api == EmbreeApi::packet16 ? "rtcOccluded16" : "rtcOccluded1"; }

EmbreeShadowPeer::EmbreeShadowPeer(const SceneShapes& shapes, const glm::dvec3& eye) : handles_(new Handles) {
  if (!shapes.spheres.empty() || !shapes.planes.empty())
    throw std::invalid_argument("the Embree peer traces triangles only; this scene has spheres or planes");
  try {
    handles_->device = rtcNewDevice("threads=0");  // every core
    if (handles_->device == nullptr) throw std::runtime_error("Embree: rtcNewDevice failed");
    const auto start = Clock::now();
    handles_->scene = rtcNewScene(handles_->device);
    rtcSetSceneBuildQuality(handles_->scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry mesh = rtcNewGeometry(handles_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), shapes.vertices.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), shapes.triangles.size()));
    check(handles_->device, "allocating the mesh");
    for (std::size_t i = 0; i < shapes.vertices.size(); ++i)
      for (int axis = 0; axis < 3; ++axis) vertices[3 * i + axis] = static_cast<float>(shapes.vertices[i][axis] - eye[axis]);
    for (std::size_t i = 0; i < shapes.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) indices[3 * i + k] = shapes.triangles[i].corners[k];
    rtcCommitGeometry(mesh);
    rtcAttachGeometry(handles_->scene, mesh);
    rtcReleaseGeometry(mesh);
    rtcCommitScene(handles_->scene);
    check(handles_->device, "building the scene");
    build_ms_ = since_ms(start);
  } catch (...) {
    this->~EmbreeShadowPeer();
    throw;
  }
}

EmbreeShadowPeer::~EmbreeShadowPeer() {
  if (handles_ == nullptr) return;
  if (handles_->scene) rtcReleaseScene(handles_->scene);
  if (handles_->device) rtcReleaseDevice(handles_->device);
  delete handles_;
  handles_ = nullptr;
}

std::string EmbreeShadowPeer::describe() const {
  const bool native16 = rtcGetDeviceProperty(handles_->device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
  return std::string("Embree ") + RTC_VERSION_STRING + ", 16-wide packets " + (native16 ? "native" : "emulated") + ", " +
         std::to_string(omp_get_max_threads()) + " threads";
}

std::vector<float> EmbreeShadowPeer::trace(const ShadowRaySet& rays, EmbreeApi api, double* milliseconds) const {
  std::vector<float> blocked(rays.size, 0.0f);
  const auto packets = static_cast<long>((rays.size + 15) / 16);
  const auto start = Clock::now();
#pragma omp parallel
  {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (api == EmbreeApi::packet16) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
#pragma omp for schedule(dynamic, 64)
    for (long packet = 0; packet < packets; ++packet) {
      const std::size_t first = static_cast<std::size_t>(packet) * 16;
      if (api == EmbreeApi::packet16) {
        alignas(64) RTCRay16 ray;
        alignas(64) int valid[16];
        for (int k = 0; k < 16; ++k) {
          const std::size_t i = first + k;
          const bool live = i < rays.size && rays.t_max[i] > 0.0f;
          valid[k] = live ? -1 : 0;
          ray.org_x[k] = live ? rays.ox[i] : 0.0f, ray.org_y[k] = live ? rays.oy[i] : 0.0f, ray.org_z[k] = live ? rays.oz[i] : 0.0f;
          ray.dir_x[k] = live ? rays.dx[i] : 1.0f, ray.dir_y[k] = live ? rays.dy[i] : 0.0f, ray.dir_z[k] = live ? rays.dz[i] : 0.0f;
          ray.tnear[k] = 0.0f;
          ray.tfar[k] = live ? rays.t_max[i] : 0.0f;
          ray.time[k] = 0.0f;
          ray.mask[k] = ~0u;
          ray.id[k] = 0, ray.flags[k] = 0;
        }
        rtcOccluded16(valid, handles_->scene, &context, &ray);
        for (int k = 0; k < 16; ++k)
          if (valid[k] && ray.tfar[k] == -std::numeric_limits<float>::infinity()) blocked[first + k] = 1.0f;
      } else {
        for (std::size_t i = first; i < std::min(first + 16, rays.size); ++i) {
          if (!(rays.t_max[i] > 0.0f)) continue;
          RTCRay ray{rays.ox[i], rays.oy[i], rays.oz[i], 0.0f, rays.dx[i], rays.dy[i], rays.dz[i], 0.0f, rays.t_max[i], ~0u, 0, 0};
          rtcOccluded1(handles_->scene, &context, &ray);
          if (ray.tfar == -std::numeric_limits<float>::infinity()) blocked[i] = 1.0f;
        }
      }
    }
  }
  if (milliseconds) *milliseconds = since_ms(start);
  return blocked;
}

}  // namespace phongcl
