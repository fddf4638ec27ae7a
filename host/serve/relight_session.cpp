#include "serve/relight_session.h"

#include <chrono>
#include <stdexcept>

#include "cl/compute_context.h"
#include "cl/device.h"

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

RelightSession::RelightSession(GBuffer gbuffer, std::string device)
    : gbuffer_(std::move(gbuffer)), beauty_(beauty_image(gbuffer_)), device_(std::move(device)) {}

RelightSession::~RelightSession() = default;

// The G-buffer never changes and a larger table only admits more indices, so a count that passed
// once passes again: this spares a scan of every pixel on each edit of a drag.
void RelightSession::check(const Scene& scene) const {
  const std::size_t count = scene.materials.size();
  std::size_t passed = smallest_passing_count_.load();
  if (count >= passed) return;
  check_materials(gbuffer_, count);
  while (count < passed && !smallest_passing_count_.compare_exchange_weak(passed, count)) {
  }
}

// The Relighter keeps its precision, ambient and background from construction: a change of those
// builds a new one (which packs the G-buffer again); lights, materials and the eye are updates.
Relighter& RelightSession::relighter_for(const Scene& scene, const RenderSettings& settings) {
  const bool same = relighter_ && relighter_settings_.precision == settings.precision &&
                    relighter_settings_.specialise == settings.specialise &&
                    relighter_->scene().ambient == scene.ambient && relighter_->scene().background == scene.background;
  if (!same) {
    relighter_.reset();  // first: two copies of a large G-buffer need not fit on the device
    RelighterOptions options;
    options.device = device_;
    options.precision = settings.precision;
    options.specialise = settings.specialise;
    relighter_.emplace(scene, gbuffer_, options);
    relighter_settings_ = settings;
  }
  relighter_->set_camera_eye(scene.camera.eye);
  relighter_->set_materials(scene.materials);
  relighter_->set_lights(scene.lights);
  return *relighter_;
}

Frame RelightSession::shade(const Scene& scene, const RenderSettings& settings) {
  if (settings.terms) return shade_with_terms(scene, settings);
  const auto start = std::chrono::steady_clock::now();
  Relighter& relighter = relighter_for(scene, settings);
  Frame frame;
  frame.image = relighter.shade();
  const ShadeTimings t = relighter.last_timings();
  frame.timings = {t.build_ms, t.kernel_ms, t.pack_ms + t.upload_ms + t.download_ms,
                   std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()};
  frame.kernel = relighter.kernel_summary();
  frame.build = t.rebuilt ? "kernel built or fetched from the cache" : "kernel reused";
  return frame;
}

Frame RelightSession::shade_with_terms(const Scene& scene, const RenderSettings& settings) {
  if (!terms_shader_) {
    terms_cache_ = std::make_unique<ProgramCache>(ProgramCache::default_directory());
    terms_shader_ = std::make_unique<PhongShader>(make_compute_context(pick_device(device_)), *terms_cache_);
  }
  ShadeOptions options{settings.precision, settings.specialise};
  options.write_terms = true;
  ShadeResult result = terms_shader_->shade(scene, gbuffer_, options);
  const ShadeTimings& t = result.timings;
  return {std::move(result.image), std::move(result.terms),
          {t.build_ms, t.kernel_ms, t.pack_ms + t.upload_ms + t.download_ms, t.total_ms},
          result.recipe.summary(), to_string(result.cache), std::move(result.warnings)};
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
