// phongcl reference: the same image from the scalar double-precision C++ reference.
#include <chrono>
#include <iostream>
#include <memory>
#include <utility>

#include "cli/lab_commands.h"
#include "cli/format.h"
#include "cli/inputs.h"
#include "cli/outputs.h"
#include "reference/reference.h"

namespace phongcl::cli {

namespace {

struct ReferenceArguments {
  SceneInputs inputs;
  ImageOutputs outputs;
};

void run_reference(const ReferenceArguments& args) {
  ImageOutputs outputs = args.outputs;
  outputs.color = args.inputs.color_config();
  refuse_outputs_over_inputs(args.inputs, outputs);
  outputs.check_destinations();
  const Scene scene = args.inputs.load_scene();
  if (args.inputs.gbuffer_file.empty()) refuse_outputs_over_inputs(args.inputs, outputs, &scene);
  const GBuffer gbuffer = args.inputs.load_gbuffer(scene);
  check_materials(gbuffer, scene.materials.size());
  const auto start = std::chrono::steady_clock::now();
  ReferenceTermImages terms;
  const Image image = reference_image(scene, gbuffer, {}, {}, args.outputs.aov_file.empty() ? nullptr : &terms);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  TermImages layers;
  layers.ambient = std::move(terms.ambient), layers.diffuse = std::move(terms.diffuse), layers.specular = std::move(terms.specular);
  const std::string written = outputs.write(image, scene.background, layers);
  std::cout << "phongcl reference: " << scene.source.string() << " + " << gbuffer.source.string() << "\n"
            << "  image      " << gbuffer.width << " x " << gbuffer.height << ", " << with_commas(gbuffer.pixel_count())
            << " pixels, " << scene.lights.size() << " lights\n"
            << "  time       " << milliseconds(ms) << " (" << mpixels_per_second(gbuffer.pixel_count(), ms)
            << ", scalar double precision, one thread)\n"
            << "  wrote      " << written << "\n";
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto args = std::make_shared<ReferenceArguments>();
  CLI::App* command = app.add_subcommand("reference", "Shade with the scalar double-precision C++ reference");
  args->inputs.add_options(*command);
  args->outputs.add_options(*command);
  args->outputs.add_aov_option(*command);
  command->callback([args] { run_reference(*args); });
}

}  // namespace phongcl::cli
