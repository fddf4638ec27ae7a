#include "serve/relight_session.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "cl/device.h"
#include "scene/mesh_files.h"

namespace phongcl {

namespace {

std::optional<Image> beauty_image(const GBuffer& gbuffer) {
  if (!gbuffer.has_beauty()) return std::nullopt;
  Image image = image_like(gbuffer);
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    float* pixel = image.pixel(i);
    for (int c = 0; c < 3; ++c) pixel[c] = gbuffer.beauty[c][i];
    pixel[3] = 1.0f;
  }
  return image;
}

}  // namespace

RelightSession::RelightSession(GBuffer gbuffer, std::string device, std::optional<std::filesystem::path> over)
    : gbuffer_(std::move(gbuffer)), beauty_(beauty_image(gbuffer_)), device_(std::move(device)) {
  if (!over) return;
  over_.emplace(*over);
  const Image& render = over_->passes().combined;
  if (render.width != gbuffer_.width || render.height != gbuffer_.height)
    throw InputError(*over, "is " + std::to_string(render.width) + " x " + std::to_string(render.height) + ", the G-buffer " +
                                std::to_string(gbuffer_.width) + " x " + std::to_string(gbuffer_.height) +
                                ": composite over the render of this G-buffer");
}

RelightSession::~RelightSession() = default;

void RelightSession::check(const Scene& scene) const {
  material_check_.check(gbuffer_, scene.materials.size());
  if (over_) group_edits(scene);  // its "rendered" lights, and no edit of a light in no group
}

std::vector<RelightSession::MeshStamp> RelightSession::mesh_stamps(const std::vector<Object>& objects) {
  std::vector<MeshStamp> stamps;
  for (const std::filesystem::path& file : mesh_files(objects)) {
    std::error_code missing;  // stamped alike each time; reading it is the Relighter's, with the error
    stamps.push_back({std::filesystem::last_write_time(file, missing), std::filesystem::file_size(file, missing)});
  }
  return stamps;
}

// The Relighter keeps its precision, ambient, background, shadow settings, whether it shades the terms
// and the objects (the shadows' geometry, meshes read from their files) from construction: a change of
// those, or of a mesh file, builds a new one (which packs the G-buffer again); lights, area lights,
// materials and the eye are updates.
Relighter& RelightSession::relighter_for(const Scene& scene, const RenderSettings& settings) {
  std::vector<MeshStamp> meshes = mesh_stamps(scene.objects);
  const bool same = relighter_ && relighter_settings_.precision == settings.precision &&
                    relighter_settings_.specialise == settings.specialise &&
                    relighter_settings_.terms == settings.terms && relighter_settings_.shadows == settings.shadows &&
                    relighter_->scene().ambient == scene.ambient &&
                    relighter_->scene().background == scene.background &&
                    relighter_->scene().objects == scene.objects && relighter_meshes_ == meshes;
  if (!same) {
    relighter_.reset();  // first: two copies of a large G-buffer need not fit on the device
    RelighterOptions options;
    options.device = device_;
    options.precision = settings.precision;
    options.specialise = settings.specialise;
    options.terms = settings.terms;
    options.shadows = settings.shadows;
    relighter_.emplace(scene, gbuffer_, options);
    if (over_) over_->forget_rendered_terms();
    relighter_settings_ = settings;
    relighter_meshes_ = std::move(meshes);
  }
  relighter_->set_camera_eye(scene.camera.eye);
  relighter_->set_materials(scene.materials);
  relighter_->set_lights(scene.lights);
  relighter_->set_area_lights(scene.area_lights);
  relighter_->set_environment(scene.environment);
  return *relighter_;
}

namespace {

// Whether solo and mute leave out a light of `group`. Over a render, a light in no group stays: its
// light cannot be taken out of the render's Combined pass.
bool left_out(const std::string& group, const RenderSettings& settings, bool over_render) {
  if (group.empty() && over_render) return false;
  const bool muted =
      !group.empty() && std::find(settings.muted.begin(), settings.muted.end(), group) != settings.muted.end();
  return muted || (!settings.solo.empty() && group != settings.solo);
}

// The scene with the lights that solo and mute leave out at colour 0, area lights too, and the
// environment at strength 0.
Scene soloed_and_muted(const Scene& scene, const RenderSettings& settings, bool over_render) {
  Scene lit = scene;
  for (Light& light : lit.lights)
    if (left_out(light.group, settings, over_render)) light.color = glm::dvec3(0.0);
  for (AreaLight& light : lit.area_lights)
    if (left_out(light.group, settings, over_render)) light.color = glm::dvec3(0.0);
  if (lit.environment && left_out(lit.environment->group, settings, over_render)) lit.environment->strength = 0.0;
  return lit;
}

}  // namespace

Frame RelightSession::shade(const Scene& scene, const RenderSettings& settings, Image canvas) {
  const auto start = std::chrono::steady_clock::now();
  const bool solo_or_mute = !settings.solo.empty() || !settings.muted.empty();
  const Scene lit = solo_or_mute ? soloed_and_muted(scene, settings, over_.has_value()) : scene;
  RenderSettings relighter_settings = settings;
  relighter_settings.terms = settings.terms || over_.has_value();  // a composite shades the changed groups' terms
  Relighter& relighter = relighter_for(lit, relighter_settings);
  Frame frame;
  if (over_) {
    RelitOver relit = over_->relight(relighter, lit, std::move(canvas));
    frame.image = std::move(relit.image);
    frame.over = OverGroups{std::move(relit.edits), std::move(relit.fits)};
    if (settings.terms) relighter.shade(frame.terms);
  } else if (settings.terms) {
    frame.image = relighter.shade(frame.terms);
  } else if (canvas.width == gbuffer_.width && canvas.height == gbuffer_.height) {
    relighter.shade_into(canvas.rgba.data(), canvas.rgba.size());
    frame.image = std::move(canvas);
  } else {
    frame.image = relighter.shade();
  }
  const ShadeReport report = relighter.last_report();
  const ShadeTimings& t = report.timings;
  frame.timings = {t.build_ms, t.kernel_ms, t.pack_ms + t.upload_ms + t.download_ms,
                   std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()};
  frame.kernel = relighter.kernel_summary();
  frame.build = t.rebuilt ? "kernel built or fetched from the cache" : "kernel reused";
  frame.warnings = report.warnings;
  return frame;
}

SurfacePick RelightSession::pick(int x, int y) const {
  if (x < 0 || y < 0 || x >= gbuffer_.width || y >= gbuffer_.height)
    throw std::out_of_range("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the " +
                            std::to_string(gbuffer_.width) + " x " + std::to_string(gbuffer_.height) + " image");
  const std::size_t i = static_cast<std::size_t>(y) * gbuffer_.width + x;
  SurfacePick pick;
  if (classify_pixel(gbuffer_, i) != PixelClass::shaded) return pick;
  pick.shaded = true;
  pick.position = {gbuffer_.position[0][i], gbuffer_.position[1][i], gbuffer_.position[2][i]};
  const glm::dvec3 normal{gbuffer_.normal[0][i], gbuffer_.normal[1][i], gbuffer_.normal[2][i]};
  pick.normal = normal == glm::dvec3(0.0) ? normal : glm::normalize(normal);
  pick.material = static_cast<int>(gbuffer_.material[i]);
  return pick;
}

std::string RelightSession::device_description() const { return describe(pick_device(device_).info); }

}  // namespace phongcl
