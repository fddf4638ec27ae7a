// phongcl reference: the same image from the scalar double-precision C++ reference.
#include <chrono>
#include <iostream>
#include <memory>

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
  refuse_outputs_over_inputs(args.inputs, args.outputs);
  args.outputs.check_destinations();
  const Scene scene = args.inputs.load_scene();
  if (args.inputs.gbuffer_file.empty()) refuse_outputs_over_inputs(args.inputs, args.outputs, &scene);
  const GBuffer gbuffer = args.inputs.load_gbuffer(scene);
  check_materials(gbuffer, scene.materials.size());
  const auto start = std::chrono::steady_clock::now();
  const Image image = reference_image(scene, gbuffer);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const std::string written = args.outputs.write(image);
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
  command->callback([args] { run_reference(*args); });
}

}  // namespace phongcl::cli
