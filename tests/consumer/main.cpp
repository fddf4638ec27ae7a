// docs/library.md's C++ usage, as written, against the installed package: shade a scene, brighten its
// first light, shade again, write both. Exits non-zero unless the relit frame is brighter where
// that light reaches and identical in the background, and the report counts every pixel; then
// relights over a render (phongcl's own, written with a pass per light group as Cycles writes them):
// doubling one group must add exactly its pass.
#include <phongcl/phongcl.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

// The scene's lights each in a group of its own, rendered by phongcl into `render` as Blender writes a
// render with light groups; then the first group doubled and composited over that render. Returns the
// largest difference from the render plus the group's pass, which must be float rounding.
float doubled_group_over_render(phongcl::Scene scene, const phongcl::GBuffer& gbuffer, const std::string& render) {
  for (std::size_t i = 0; i < scene.lights.size(); ++i) scene.lights[i].group = "group" + std::to_string(i);
  scene.rendered = phongcl::RenderedLights{scene.lights, scene.area_lights};
  phongcl::RelighterOptions options;
  options.terms = true;
  phongcl::Relighter relighter(scene, gbuffer, options);
  phongcl::TermImages terms;
  const phongcl::Image combined = relighter.shade(terms);
  std::vector<phongcl::ExrLayer> layers = {{"ViewLayer.Combined", &combined, true}};
  for (std::size_t g = 0; g < terms.groups.size(); ++g)
    layers.push_back({"ViewLayer.Combined_" + terms.group_names[g], &terms.groups[g], false});
  phongcl::ExrWriteOptions keep;
  keep.keep_color_where_transparent = true;
  phongcl::write_layered_exr(layers, render, keep);

  scene.lights[0].color *= 2.0;
  relighter.set_lights(scene.lights);
  phongcl::RenderCompositor over(render);
  const phongcl::Image composite = over.relight(relighter, relighter.scene()).image;
  float worst = 0.0f;
  for (std::size_t i = 0; i < composite.pixel_count(); ++i)
    for (int c = 0; c < 4; ++c) {
      const float expected = combined.pixel(i)[c] + (c < 3 ? terms.groups[0].pixel(i)[c] : 0.0f);
      worst = std::fmax(worst, std::fabs(composite.pixel(i)[c] - expected));
    }
  return worst;
}

}  // namespace

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
    const float over_error = doubled_group_over_render(phongcl::load_scene(argv[1]), gbuffer,
                                                       std::string(argv[3]) + "/render.exr");
    std::printf("phongcl_consumer: one light group doubled over phongcl's render: %g from the render plus its pass\n",
                over_error);
    return brighter > 0 && darker == 0 && background_changed == 0 && counted && over_error < 1e-4f ? 0 : 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "phongcl_consumer: %s\n", error.what());
    return 1;
  }
}
