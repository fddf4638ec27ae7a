#include "serve/relight_session.h"

#include <stdexcept>

namespace phongcl {

RelightSession::RelightSession(GBuffer gbuffer, ComputeContext compute, ProgramCache& cache)
    : gbuffer_(std::move(gbuffer)), shader_(std::move(compute), cache) {}

void RelightSession::check(const Scene& scene) const { check_materials(gbuffer_, scene.materials.size()); }

Frame RelightSession::shade(const Scene& scene, const RenderSettings& settings) {
  ShadeOptions options{settings.precision, settings.specialise};
  options.write_terms = settings.terms;
  ShadeResult result = shader_.shade(scene, gbuffer_, options);
  const ShadeTimings& t = result.timings;
  Frame frame{std::move(result.image), std::move(result.terms),
              {t.build_ms, t.kernel_ms, t.pack_ms + t.upload_ms + t.download_ms, t.total_ms},
              result.recipe.summary(), to_string(result.cache), std::move(result.warnings)};
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

}  // namespace phongcl
