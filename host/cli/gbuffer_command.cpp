// phongcl gbuffer: ray-cast the scene's geometry into a G-buffer EXR.
#include <chrono>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/format.h"
#include "common/error.h"
#include "common/same_file.h"
#include "raycast/raycast.h"
#include "scene/mesh_files.h"

namespace phongcl::cli {

namespace {

struct GBufferArguments {
  std::string scene_file, out_file;
  bool half = false;
};

void run_gbuffer(const GBufferArguments& args) {
  const Scene scene = load_scene(args.scene_file);
  const std::filesystem::path out = args.out_file.empty() ? scene.gbuffer : std::filesystem::path(args.out_file);
  if (out.empty()) throw InputError(scene.source, "no output: give --out or a \"gbuffer\" entry in the scene");
  // Before the meshes are read: the output may replace neither the scene nor one of its meshes.
  std::vector<NamedFile> files{{"--scene", args.scene_file}};
  for (const std::filesystem::path& mesh : mesh_files(scene.objects)) files.push_back(mesh_input(mesh));
  files.push_back({args.out_file.empty() ? "the scene's \"gbuffer\" entry" : "--out", out, true});
  refuse_shared_files(files);
  const auto start = std::chrono::steady_clock::now();
  const GBuffer gbuffer = generate_gbuffer(scene);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  write_gbuffer(gbuffer, out, args.half ? ExrPixelType::half : ExrPixelType::float32);
  std::size_t hits = 0;
  for (float material : gbuffer.material) hits += material >= 0.0f;
  std::cout << "phongcl gbuffer: " << scene.source.string() << "\n"
            << "  image      " << gbuffer.width << " x " << gbuffer.height << ", " << with_commas(hits)
            << " pixels hit geometry, " << with_commas(gbuffer.pixel_count() - hits) << " background\n"
            << "  time       ray casting " << milliseconds(ms) << " (" << mpixels_per_second(gbuffer.pixel_count(), ms)
            << ", one thread)\n"
            << "  wrote      " << out.string() << (args.half ? " (half)" : " (float32)") << "\n";
}

}  // namespace

void add_gbuffer_command(CLI::App& app) {
  auto args = std::make_shared<GBufferArguments>();
  CLI::App* command = app.add_subcommand("gbuffer", "Ray-cast the scene's objects into a G-buffer EXR");
  command->add_option("--scene", args->scene_file, "Scene file (JSON)")->required();
  command->add_option("--out", args->out_file, "Output EXR (default: the scene's \"gbuffer\" entry)");
  command->add_flag("--half", args->half, "Write half channels instead of float32");
  command->callback([args] { run_gbuffer(*args); });
}

}  // namespace phongcl::cli
