// docs/library.md's C++ usage, as written, against the installed package: shade a scene, brighten its
// first light, shade again, write both. Exits non-zero unless the relit frame is brighter where
// that light reaches and identical in the background, and the report counts every pixel.
#include <phongcl/phongcl.hpp>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: phongcl_consumer SCENE GBUFFER OUT_DIR\n");
    return 2;
  }
  try {
    phongcl::Scene scene = phongcl::load_scene(argv[1]);
    phongcl::GBuffer gbuffer = phongcl::read_gbuffer(argv[2]);
    phongcl::Relighter relighter(scene, gbuffer);
    const phongcl::Image before = relighter.shade();
    scene.lights[0].color *= 2.0;
    relighter.set_lights(scene.lights);
    const phongcl::Image image = relighter.shade();
    phongcl::write_exr(std::string(argv[3]) + "/before.exr", before);
    phongcl::write_exr(std::string(argv[3]) + "/out.exr", image);

    std::size_t brighter = 0, darker = 0, background_changed = 0;
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
      const float* a = before.pixel(i);
      const float* b = image.pixel(i);
      if (a[3] == 0.0f) {
        background_changed += a[0] != b[0] || a[1] != b[1] || a[2] != b[2];
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        brighter += b[c] > a[c];
        darker += b[c] < a[c];
      }
    }
    const phongcl::ShadeReport report = relighter.last_report();
    const bool counted = report.counts.shaded + report.counts.background == image.pixel_count();
    std::printf("phongcl_consumer: %dx%d on %s; after doubling light 0: %zu channel values brighter, %zu darker, "
                "%zu background pixels changed; kernel %.2f ms; %zu pixels shaded (%s)\n",
                relighter.width(), relighter.height(), phongcl::describe(relighter.device()).c_str(), brighter,
                darker, background_changed, report.timings.kernel_ms, report.counts.shaded,
                report.kernel_summary.c_str());
    return brighter > 0 && darker == 0 && background_changed == 0 && counted ? 0 : 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "phongcl_consumer: %s\n", error.what());
    return 1;
  }
}
