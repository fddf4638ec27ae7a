#pragma once
// The server's only contact with the shading library: one G-buffer kept on the device from frame
// to frame, shaded for whatever scene the page holds now, and read back under the cursor.
#include <string>

#include <glm/glm.hpp>

#include "cl/program_cache.h"
#include "gbuffer/gbuffer.h"
#include "image/image.h"
#include "scene/scene.h"
#include "shading/phong_shader.h"

namespace phongcl {

struct RenderSettings {
  Precision precision = Precision::precise;
  bool specialise = true;
  bool terms = false;  // also shade the ambient, diffuse and specular terms separately
};

// Milliseconds. transfer: packing and moving the G-buffer and the image between host and device.
struct FrameTimings {
  double build_ms = 0.0, kernel_ms = 0.0, transfer_ms = 0.0, shade_ms = 0.0;
};

struct Frame {
  Image image;
  TermImages terms;        // empty unless RenderSettings::terms
  FrameTimings timings;
  std::string kernel;      // what was compiled in: "precise, specialised: 2 point (unrolled) + ..."
  std::string build;       // "compiled" or a cache hit, as `shade` prints it
  std::vector<std::string> warnings;
};

// What the G-buffer holds at one pixel (row 0 at the top).
struct SurfacePick {
  bool shaded = false;  // false: background, the other fields are zero
  glm::dvec3 position{0.0}, normal{0.0};  // normal unit length (zero if the G-buffer's is zero)
  int material = -1;
};

class RelightSession {
 public:
  RelightSession(GBuffer gbuffer, ComputeContext compute, ProgramCache& cache);

  // Throws InputError (naming the G-buffer) when the scene cannot shade this G-buffer, e.g. a
  // material index beyond the scene's table: call it before accepting a scene.
  void check(const Scene& scene) const;
  Frame shade(const Scene& scene, const RenderSettings& settings);
  // Throws std::out_of_range outside the image.
  SurfacePick pick(int x, int y) const;

  int width() const { return gbuffer_.width; }
  int height() const { return gbuffer_.height; }
  const GBuffer& gbuffer() const { return gbuffer_; }

 private:
  GBuffer gbuffer_;
  PhongShader shader_;
};

}  // namespace phongcl
