#include "shading/frame_memory.h"

#include "geometry/device_geometry.h"
#include "geometry/scene_shapes.h"

namespace phongcl {
namespace {

constexpr double kRgbaBytes = 4 * sizeof(float);

std::string pixels_text(const GBuffer& gbuffer) {
  return std::to_string(gbuffer.width) + "x" + std::to_string(gbuffer.height) + " pixels";
}

}  // namespace

// Per pixel: the packed planes (float; the half variant's staging is float too), the image on the
// device and the host; with terms, three term planes per term and per group on the device (as the
// kernel writes them) and an RGBA image each on the host.
std::vector<MemoryNeed> frame_memory_needs(const GBuffer& gbuffer, const Recipe& recipe) {
  const double pixels = static_cast<double>(gbuffer.pixel_count());
  std::vector<MemoryNeed> needs = {
      {"the G-buffer packed for the device and the image (" + pixels_text(gbuffer) + ")",
       pixels * (recipe.plane_count() * sizeof(float) + 2 * kRgbaBytes)}};
  if (!recipe.write_terms) return needs;
  constexpr double kTermBytes = 3 * sizeof(float) + kRgbaBytes;
  needs.push_back({"the ambient, diffuse and specular images", pixels * 3 * kTermBytes});
  const std::size_t groups = recipe.light_groups.size();
  if (groups > 0)
    needs.push_back({"the images of " + std::to_string(groups) + " light groups (" + pixels_text(gbuffer) + " each)",
                     pixels * static_cast<double>(groups) * kTermBytes});
  return needs;
}

std::vector<MemoryNeed> geometry_memory_needs(const Scene& scene, const Recipe& recipe) {
  if (recipe.shadows != ShadowMode::geometry) return {};
  const ShapeCounts counts = count_shapes(scene.objects);
  return {{"the shadow geometry (" + std::to_string(counts.triangles) + " triangles, meshes counted per instance: " +
               std::to_string(counts.mesh_instances) + ")",
           shadow_geometry_bytes(counts)}};
}

void check_frame_memory(const std::vector<MemoryNeed>& frame, const std::vector<MemoryNeed>& geometry) {
  std::vector<MemoryNeed> needs = frame;
  needs.insert(needs.end(), geometry.begin(), geometry.end());
  check_memory("shading this frame", needs, memory_limit());
}

}  // namespace phongcl
