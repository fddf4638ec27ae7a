#pragma once
// The server's only contact with the shading library: the G-buffer resident on the device
// (phongcl::Relighter), shaded for whatever scene the page holds now (with the AOV terms when the
// page shows one), and read back under the cursor.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "composite/relight_over.h"
#include "gbuffer/gbuffer.h"
#include "gbuffer/material_check.h"
#include "image/image.h"
#include "phongcl/relighter.hpp"
#include "scene/scene.h"

namespace phongcl {

struct RenderSettings {
  Precision precision = Precision::precise;
  bool specialise = true;
  bool terms = false;  // also shade the ambient, diffuse and specular terms separately
  ShadowSettings shadows;  // how lights with "shadows": true cast them
  // Light groups shown alone or left out: the other groups' lights (ungrouped ones too), or the
  // muted groups', are shaded with colour 0 (on the host: the same kernel, no rebuild).
  std::string solo;                // empty: none
  std::vector<std::string> muted;
};

// Milliseconds. transfer: packing and moving data between host and device (the G-buffer only
// when the eye moved); shade: wall clock of the whole frame.
struct FrameTimings {
  double build_ms = 0.0, kernel_ms = 0.0, transfer_ms = 0.0, shade_ms = 0.0;
};

// Over a render: what became of each of its light groups in this frame (composite/relight_over.h).
struct OverGroups {
  std::vector<GroupEdit> edits;
  std::map<std::string, GroupFit> fits;  // per re-shaded group the render had
};

struct Frame {
  Image image;                // over a render: the composite
  std::optional<OverGroups> over;
  TermImages terms;        // empty unless RenderSettings::terms
  FrameTimings timings;
  std::string kernel;      // what was compiled in: "precise, specialised: 2 point (unrolled) + ..."
  std::string build;       // whether this frame built (or fetched) a kernel
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
  // `device` as `phongcl shade --device` takes it (empty: the default device). With `over`, a render
  // of this G-buffer with light-group passes, every frame is composited over it: unchanged groups
  // stay as rendered, solo and mute take groups' passes out (the world and lights in no group stay).
  // InputError naming the render when it cannot be read or is of another size.
  RelightSession(GBuffer gbuffer, std::string device, std::optional<std::filesystem::path> over = std::nullopt);
  ~RelightSession();

  // Throws InputError (naming the G-buffer) when the scene cannot shade this G-buffer, e.g. a
  // material index beyond the scene's table, or (naming the scene) when it cannot be composited over
  // the render (composite/group_edits.h): call it before accepting a scene.
  void check(const Scene& scene) const;
  // Not thread-safe: one render thread calls it. `canvas`, an earlier frame's image that nobody
  // reads any more, is shaded into when it has this G-buffer's size: a new 1080p image costs a
  // 33 MB allocation whose every page faults in on first write, several times the kernel's time.
  Frame shade(const Scene& scene, const RenderSettings& settings, Image canvas = {});
  // Throws std::out_of_range outside the image.
  SurfacePick pick(int x, int y) const;

  int width() const { return gbuffer_.width; }
  int height() const { return gbuffer_.height; }
  const GBuffer& gbuffer() const { return gbuffer_; }
  // The renderer's own image from the G-buffer file (alpha 1), or nullptr when it has none.
  const Image* beauty() const { return beauty_ ? &*beauty_ : nullptr; }
  // The render every frame is composited over, or nullptr.
  const RenderCompositor* over() const { return over_ ? &*over_ : nullptr; }
  std::string device_description() const;

 private:
  // A mesh file as it was when the Relighter took the scene: one rewritten in place is read again.
  struct MeshStamp {
    std::filesystem::file_time_type written;
    std::uintmax_t bytes = 0;
    bool operator==(const MeshStamp&) const = default;
  };
  static std::vector<MeshStamp> mesh_stamps(const std::vector<Object>& objects);
  Relighter& relighter_for(const Scene& scene, const RenderSettings& settings);

  GBuffer gbuffer_;
  MaterialCheck material_check_;  // of check()
  std::optional<Image> beauty_;
  std::optional<RenderCompositor> over_;
  std::string device_;
  std::optional<Relighter> relighter_;
  RenderSettings relighter_settings_;
  std::vector<MeshStamp> relighter_meshes_;
};

}  // namespace phongcl
