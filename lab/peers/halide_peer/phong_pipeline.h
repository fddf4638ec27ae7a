#pragma once
// The Phong formula of the C++ peers (host/peers/phong_pixel.h, float_math.h) as a Halide pipeline
// over the same packed structure-of-arrays input, with a choice of schedules.
#include <string>
#include <vector>

#include <Halide.h>

namespace phongcl::halide_peer {

struct PipelineInputs {
  // Frame: one plane per component, padded pixels (peers/packed_frame.h).
  Halide::ImageParam px{Halide::Float(32), 1, "px"}, py{Halide::Float(32), 1, "py"}, pz{Halide::Float(32), 1, "pz"};
  Halide::ImageParam nx{Halide::Float(32), 1, "nx"}, ny{Halide::Float(32), 1, "ny"}, nz{Halide::Float(32), 1, "nz"};
  Halide::ImageParam material{Halide::Int(32), 1, "material"};  // -1: background
  // Scene: materials(entry, attribute) with the background at entry 0; lights(light, attribute), at
  // least one row each (Halide wants a non-empty buffer) of which the first *_count are lights.
  Halide::ImageParam materials{Halide::Float(32), 2, "materials"};
  Halide::ImageParam point_lights{Halide::Float(32), 2, "point_lights"};
  Halide::ImageParam directional_lights{Halide::Float(32), 2, "directional_lights"};
  Halide::Param<int> point_count{"point_count"}, directional_count{"directional_count"};
  Halide::Param<int> chunk{"chunk", 8192, 64, 1 << 30};  // pixels per parallel task
};

// Column order of the scene buffers.
enum MaterialAttribute { kAmbientR, kAmbientG, kAmbientB, kKdR, kKdG, kKdB, kKsR, kKsG, kKsB, kShininess, kAlpha, kMaterialAttributes };
enum LightAttribute { kLightX, kLightY, kLightZ, kLightR, kLightG, kLightB, kLightAttributes };

struct Schedule {
  std::string name, description;
};
// Every schedule, the default first: the fastest here in CPU time per frame at 1 to 64 lights
// (1080p; vector64 beat vector32 by 7-17% and the L1 tiles by 16-31%; docs/performance.md "Throughput").
const std::vector<Schedule>& schedules();

// rgba(c, i): 4 floats per pixel, the layout the kernel writes. Throws std::invalid_argument for an
// unknown schedule name.
Halide::Func phong_pipeline(const PipelineInputs& in, const std::string& schedule);

}  // namespace phongcl::halide_peer
