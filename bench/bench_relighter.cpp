// The C++ side of bench/relighter_benchmark.py, written against the public API only: a light
// orbiting the scene in N steps through phongcl::Relighter, one untimed warm-up frame (kernel
// build, G-buffer upload), then per frame the wall clock of set_lights + shade_into and the
// Relighter's own kernel (profiling events) and download times. Prints one JSON object.
//   bench_relighter SCENE GBUFFER STEPS
#include <phongcl/phongcl.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

// The scene's lights with the first point light moved `step` of `steps` around the look-at point
// at its height and distance (as examples/relight_turntable.py's orbit()).
std::vector<phongcl::Light> orbit(const phongcl::Scene& scene, int step, int steps) {
  std::vector<phongcl::Light> lights = scene.lights;
  for (phongcl::Light& light : lights) {
    if (light.type != phongcl::LightType::point) continue;
    const glm::dvec3 centre = scene.camera.look_at;
    const glm::dvec3 offset = light.position - centre;
    const double radius = std::hypot(offset.x, offset.z);
    const double angle = std::atan2(offset.z, offset.x) + 2 * M_PI * step / steps;
    light.position = {centre.x + radius * std::cos(angle), light.position.y, centre.z + radius * std::sin(angle)};
    break;
  }
  return lights;
}

std::string json_list(const std::vector<double>& values) {
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + std::to_string(values[i]);
  return text + "]";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: bench_relighter SCENE GBUFFER STEPS\n");
    return 2;
  }
  try {
    const phongcl::Scene scene = phongcl::load_scene(argv[1]);
    phongcl::Relighter relighter(scene, phongcl::read_gbuffer(argv[2]));
    const int steps = std::stoi(argv[3]);
    std::vector<float> image(4 * static_cast<std::size_t>(relighter.width()) * relighter.height());
    relighter.shade_into(image.data(), image.size());  // warm-up: build, upload, first touch
    std::vector<double> frame_ms, kernel_ms, download_ms;
    for (int step = 0; step < steps; ++step) {
      const auto start = std::chrono::steady_clock::now();
      relighter.set_lights(orbit(scene, step, steps));
      relighter.shade_into(image.data(), image.size());
      frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      kernel_ms.push_back(relighter.last_timings().kernel_ms);
      download_ms.push_back(relighter.last_timings().download_ms);
    }
    std::printf("{\"width\": %d, \"height\": %d, \"frame_ms\": %s, \"kernel_ms\": %s, \"download_ms\": %s}\n",
                relighter.width(), relighter.height(), json_list(frame_ms).c_str(), json_list(kernel_ms).c_str(),
                json_list(download_ms).c_str());
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_relighter: %s\n", error.what());
    return 1;
  }
}
