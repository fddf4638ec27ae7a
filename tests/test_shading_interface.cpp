// The interface between host and kernel: phong_shade's arguments as the host sets them
// (shading/phong_arguments.h) against the kernel's own parameter names, read back from a build with
// -cl-kernel-arg-info (two buffers swapped on either side fail here, not as a wrong image); and the
// kernels built in the variants the recipe makes, on whatever device this runs (PoCL in ctest,
// Oclgrind's front end in scripts/checks/40-oclgrind.sh), once with -cl-opt-disable.
#include <cstdlib>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "cl/kernel_source.h"
#include "opencl_required.h"
#include "shading/phong_arguments.h"
#include "shading/phong_launch.h"
#include "shading/tile_culling.h"
#include "shading_support.h"
#include "shaped_lights.h"

namespace phongcl {
namespace {

using testing::random_scene;
using testing::RandomSceneSpec;
using testing::ShapedLightSpec;

// `file` built with `options`; throws with the build log when it does not build.
cl::Program built(const ComputeContext& compute, const std::string& file, const std::string& options) {
  cl::Program program(compute.context, load_kernel_source(file));
  try {
    program.build(options.c_str());
  } catch (const cl::BuildError& error) {
    std::string log;
    for (const auto& [device, text] : error.getBuildLog()) log += text;
    throw std::runtime_error(file + " does not build with " + options + ":\n" + log);
  }
  return program;
}

std::vector<std::string> kernel_parameter_names(const ComputeContext& compute, const std::string& options) {
  const cl::Kernel kernel(built(compute, "phong.cl", options + " -cl-kernel-arg-info"), "phong_shade");
  std::vector<std::string> names;
  for (cl_uint i = 0; i < kernel.getInfo<CL_KERNEL_NUM_ARGS>(); ++i) {
    std::string name = kernel.getArgInfo<CL_KERNEL_ARG_NAME>(i);
    name.erase(name.find_last_not_of('\0') + 1);  // some implementations count the terminator
    names.push_back(name);
  }
  return names;
}

TEST(KernelInterface, HostSetsArgumentsInTheKernelsParameterOrder) {
  PHONGCL_REQUIRE_DEVICE(shader);
  const auto [scene, gbuffer] = random_scene({}, 21);
  ShadeOptions general;
  general.specialise = false;
  ShadeOptions culled_with_terms;
  culled_with_terms.culling = Culling::tiled;
  culled_with_terms.write_terms = true;
  for (const ShadeOptions& options : {ShadeOptions{}, general, culled_with_terms}) {
    const Recipe recipe = make_recipe(scene, gbuffer, shader.compute().device.info, options);
    EXPECT_EQ(kernel_parameter_names(shader.compute(), recipe.build_options()), phong_argument_names())
        << recipe.build_options();
  }
}

// Builds phong.cl for `recipe` with `extra` options and shades one work-item of background pixels
// with it (no lights: the counts are 0 in the general kernel and the loops of a specialised one
// read zeroed tables).
void launch_once(const ComputeContext& compute, const Recipe& recipe, const std::string& extra) {
  cl::Kernel kernel(built(compute, "phong.cl", recipe.build_options() + extra), "phong_shade");
  const auto lanes = static_cast<std::size_t>(recipe.lanes);
  auto zeros = [&](std::size_t bytes) {
    std::vector<unsigned char> values(bytes, 0);
    return cl::Buffer(compute.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, values.data());
  };
  std::vector<cl_int> background(lanes, PHONGCL_BACKGROUND);
  const cl::Buffer index(compute.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, lanes * sizeof(cl_int),
                         background.data());
  // Every table of every block at offset 0 of one zeroed buffer.
  const cl::Buffer tables = zeros(4096);
  PhongArguments arguments{.planes = zeros(recipe.plane_count() * lanes * sizeof(cl_float)),
                           .material_index = index,
                           .scene = tables,
                           .tile_lists = tables,
                           .shadow_geometry = tables,
                           .shadow_lists = tables,
                           .out_rgba = zeros(PHONGCL_OUTPUT_PLANES * lanes * sizeof(cl_float)),
                           .out_terms = zeros(PHONGCL_TERM_PLANES * lanes * sizeof(cl_float))};
  arguments.frame.plane_stride = static_cast<cl_uint>(lanes);
  arguments.frame.grid = {static_cast<cl_uint>(lanes), 16, 1, 0, 0};
  launch_phong(kernel, compute, arguments, lanes, recipe.lanes);
  compute.queue.finish();
}

// Scenes that between them switch every recipe flag both ways: light types and counts in the code or
// not, every light shape, linking of one and two words, per-pixel materials, one material, tables
// picked by selects and gathered, no lights at all.
std::vector<std::pair<Scene, GBuffer>> variant_scenes() {
  std::vector<std::pair<Scene, GBuffer>> scenes;
  scenes.push_back(random_scene({}, 31));
  auto shaped = random_scene({}, 32);
  ShapedLightSpec every_shape;
  every_shape.linking = true;
  testing::add_shaped_lights(shaped.first, every_shape, 33);
  scenes.push_back(shaped);
  RandomSceneSpec per_pixel;
  per_pixel.materials = 1;
  per_pixel.per_pixel_materials = true;
  scenes.push_back(random_scene(per_pixel, 34));
  RandomSceneSpec many;
  many.point_lights = 20;
  many.directional_lights = 17;
  many.materials = 40;
  auto crowded = random_scene(many, 35);
  ShapedLightSpec mixed;
  mixed.mixed_falloff = mixed.linking = true;
  testing::add_shaped_lights(crowded.first, mixed, 36);
  scenes.push_back(crowded);
  RandomSceneSpec dark;
  dark.point_lights = dark.directional_lights = 0;
  scenes.push_back(random_scene(dark, 37));
  return scenes;
}

// Built on $PHONGCL_TEST_DEVICE where set (scripts/checks/40-oclgrind.sh names Oclgrind, which the
// default choice passes over as a simulator), else on the default device.
TEST(KernelVariants, EveryVariantBuilds) {
  PHONGCL_REQUIRE_OPENCL(!list_devices().empty());
  const char* named = std::getenv("PHONGCL_TEST_DEVICE");
  const ComputeContext compute = make_compute_context(pick_device(named ? named : ""));
  const DeviceInfo& device = compute.device.info;
  std::cout << "building on " << device.name << "\n";
  std::set<std::string> phong_options, cull_options;
  auto add = [&](const Scene& scene, const GBuffer& gbuffer, const ShadeOptions& options) {
    if (options.precision == Precision::double_precision && !device.has_fp64) return;
    const Recipe recipe = make_recipe(scene, gbuffer, device, options);
    phong_options.insert(recipe.build_options());
    for (int block_boxes : {4, 8}) cull_options.insert(culling_options(recipe.build_options(), block_boxes));
  };
  const auto scenes = variant_scenes();
  // Every scene one pixel per work-item, culled with terms, and general; the shaped scene in every precision.
  ShadeOptions narrow, culled, general;
  narrow.lanes = 1;
  culled.culling = Culling::tiled;
  culled.write_terms = true;
  general.specialise = false;
  for (const auto& [scene, gbuffer] : scenes)
    for (const ShadeOptions& options : {narrow, culled, general}) add(scene, gbuffer, options);
  for (Precision precision : all_precisions())
    for (ShadeOptions options : {narrow, culled}) {
      options.precision = precision;
      add(scenes[1].first, scenes[1].second, options);
    }
  for (int lanes : {2, 4, 8}) {
    ShadeOptions options;
    options.lanes = lanes;
    add(scenes[1].first, scenes[1].second, options);
  }
  // Shadows, every light casting them: marched (no objects), and traced (a sphere), culled too.
  Scene shadowed = scenes[1].first;
  for (Light& light : shadowed.lights) light.shadows = true;
  add(shadowed, scenes[1].second, narrow);
  Object sphere;
  sphere.kind = Object::Kind::sphere;
  shadowed.objects.push_back(sphere);
  for (const ShadeOptions& options : {narrow, culled}) add(shadowed, scenes[1].second, options);
  // Area lights, a rect and a disk: one pixel and a vector per work-item, culled, general, in double.
  Scene lit = scenes[1].first;
  lit.area_lights = {{AreaShape::rect, {0.3, 1.5, 2.0}, {0, -1, 0}, {0, 0, 1}, {1.0, 0.5}, {1, 1, 1}},
                     {AreaShape::disk, {-0.4, 1.0, 1.0}, {0.2, -1, 0}, {0, 1, 0}, glm::dvec2(0.7), {1, 0.5, 0.2}, 4.0}};
  ShadeOptions in_double;
  in_double.precision = Precision::double_precision;
  for (const ShadeOptions& options : {narrow, culled, general, ShadeOptions{}, in_double}) add(lit, scenes[1].second, options);
  // Unoptimised too (-cl-opt-disable), built and launched once: an implementation may link a kernel
  // only for its first launch.
  const auto& [scene, gbuffer] = scenes[1];
  for (const ShadeOptions& options : {general, ShadeOptions{}}) {
    const Recipe recipe = make_recipe(scene, gbuffer, device, options);
    try {
      launch_once(compute, recipe, " -cl-opt-disable");
    } catch (const std::exception& error) {
      ADD_FAILURE() << "-cl-opt-disable: " << error.what();
    }
  }
  auto expect_builds = [&](const std::string& file, const std::set<std::string>& variants) {
    for (const std::string& options : variants) {
      try {
        built(compute, file, options);
      } catch (const std::exception& error) {
        ADD_FAILURE() << error.what();
      }
    }
  };
  expect_builds("phong.cl", phong_options);
  expect_builds("cull.cl", cull_options);
  std::cout << phong_options.size() << " phong.cl and " << cull_options.size() << " cull.cl variants built\n";
}

}  // namespace
}  // namespace phongcl
