// shade's sequence mode: frames through the read / shade / write pipeline (sequence/frame_pipeline.h),
// resumable because every output is written atomically: a frame whose outputs exist is done.
#include "cli/shade_sequence.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <thread>

#include <phongcl/relighter.hpp>

#include "cli/format.h"
#include "cli/sequence_progress.h"
#include "common/same_file.h"
#include "exr/exr_channels.h"
#include "sequence/frame_list.h"
#include "sequence/frame_pattern.h"
#include "sequence/shard.h"
#include "sequence/stop_signal.h"

namespace phongcl::cli {

namespace {

using Clock = std::chrono::steady_clock;

// The patterns of one run, and each frame's inputs and outputs made from them.
struct SequenceFiles {
  FramePattern scene, gbuffer, exr, png, aov;

  SequenceFiles(const SceneInputs& inputs, const ImageOutputs& outputs)
      : scene(inputs.scene_file), gbuffer(inputs.gbuffer_file), exr(outputs.exr_file), png(outputs.png_file),
        aov(outputs.aov_file) {
    const std::pair<const FramePattern*, const char*> written[] = {{&exr, "--out"}, {&png, "--png"}, {&aov, "--aov"}};
    for (const auto& [pattern, option] : written)
      if (!pattern->text().empty() && !pattern->is_pattern())
        throw std::invalid_argument(std::string(option) + " '" + pattern->text() +
                                    "' names one file for every frame: give a pattern such as lit.####.exr");
  }

  SceneInputs inputs_of(const SceneInputs& inputs, int frame) const {
    SceneInputs framed = inputs;
    framed.scene_file = scene.path(frame).string();
    if (!gbuffer.text().empty()) framed.gbuffer_file = gbuffer.path(frame).string();
    return framed;
  }
  ImageOutputs outputs_of(const ImageOutputs& outputs, int frame) const {
    ImageOutputs framed = outputs;
    auto path = [frame](const FramePattern& pattern) { return pattern.text().empty() ? "" : pattern.path(frame).string(); };
    framed.exr_file = path(exr);
    framed.png_file = path(png);
    framed.aov_file = path(aov);
    return framed;
  }
  // Every file of every frame, each named by its option and pattern, for refuse_shared_files.
  std::vector<NamedFile> named_files(const SceneInputs& inputs, const ImageOutputs& outputs,
                                     const std::vector<int>& frames) const {
    const std::pair<const char*, const FramePattern*> patterns[] = {
        {"--scene", &scene}, {"--gbuffer", &gbuffer}, {"--out", &exr}, {"--png", &png}, {"--aov", &aov}};
    std::vector<NamedFile> files;
    for (const int frame : frames) {
      for (const auto& list : {inputs_of(inputs, frame).named_files(), outputs_of(outputs, frame).named_files()})
        for (NamedFile file : list) {
          for (const auto& [option, pattern] : patterns)
            if (file.option == option && pattern->is_pattern()) file.pattern = pattern->text();
          files.push_back(std::move(file));
        }
    }
    return files;
  }
  // Outputs are written atomically, so one that exists is whole; the frame is done when all do.
  bool done(const ImageOutputs& outputs, int frame) const {
    const ImageOutputs framed = outputs_of(outputs, frame);
    for (const std::string* file : {&framed.exr_file, &framed.png_file, &framed.aov_file})
      if (!file->empty() && !std::filesystem::exists(*file)) return false;
    return true;
  }
};

std::vector<int> requested_frames(const SequenceOptions& sequence, const SequenceFiles& files) {
  if (!sequence.frames.empty()) return parse_frame_list(sequence.frames);
  const FramePattern& source = files.gbuffer.is_pattern() ? files.gbuffer : files.scene;
  if (!source.is_pattern()) throw std::invalid_argument("no frames: give --frames, or a --gbuffer or --scene frame pattern");
  std::vector<int> frames = source.frames_on_disk();
  if (frames.empty()) throw std::invalid_argument("no frames: no file matches '" + source.text() + "'");
  return frames;
}

// --shard, else the Slurm job array's task (said so on the first line), else every frame.
Shard pick_shard(const SequenceOptions& sequence, std::string& origin) {
  if (!sequence.shard.empty()) {
    origin = "--shard";
    return parse_shard(sequence.shard);
  }
  if (const std::optional<Shard> slurm = shard_from_slurm([](const char* name) { return std::getenv(name); })) {
    origin = "Slurm job array task " + std::string(std::getenv("SLURM_ARRAY_TASK_ID"));
    return *slurm;
  }
  return {};
}

std::string frame_span(const std::vector<int>& frames) {
  if (frames.empty()) return "none";
  return std::to_string(frames.front()) + (frames.size() > 1 ? "-" + std::to_string(frames.back()) : "");
}

std::string seconds_text(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f s", ms / 1000.0);
  return text;
}

}  // namespace

void SequenceOptions::add_options(CLI::App& command) {
  command.add_option("--frames", frames, "Frames to shade: 1001-1240, 1001-1240x2 (every 2nd), 1001,1010-1020 (default: the G-buffer frames on disk)");
  command.add_option("--shard", shard, "Shade the I-th, I+N-th, ... frame of the list (0-based); default in a Slurm job array: its task");
  command.add_flag("--overwrite", overwrite, "Shade frames whose outputs exist (default: skip them, they are done)");
  command.add_flag("--keep-going", keep_going, "After a failed frame shade the others; exit non-zero listing the failed frames");
  command.add_option("--threads", threads, "EXR (de)compression threads (default: every core)")->check(CLI::Range(1, 1024));
  command.add_option("--compression", compression, "EXR output compression (default: the input's)")
      ->check(CLI::IsMember({"none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"}));
}

bool SequenceOptions::wanted(const SceneInputs& inputs, const ImageOutputs& outputs) const {
  if (!frames.empty()) return true;
  for (const std::string* name : {&inputs.scene_file, &inputs.gbuffer_file, &outputs.exr_file, &outputs.png_file, &outputs.aov_file})
    if (FramePattern(*name).is_pattern()) return true;
  return false;
}

void SequenceOptions::start_exr_threads() const {
  exr::set_exr_threads(threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
}

ExrCompression SequenceOptions::output_compression(ExrCompression input) const {
  return compression.empty() ? input : exr::parse_compression(compression);
}

void run_shade_sequence(const SceneInputs& inputs, const ImageOutputs& given_outputs, const RelighterOptions& options,
                        const SequenceOptions& sequence) {
  const auto start = Clock::now();
  ImageOutputs outputs = given_outputs;
  outputs.color = inputs.color_config();  // loaded before the pipeline's threads share it
  const SequenceFiles files(inputs, outputs);
  const std::vector<int> requested = requested_frames(sequence, files);
  refuse_shared_files(files.named_files(inputs, outputs, requested));
  std::string shard_origin;
  const Shard shard = pick_shard(sequence, shard_origin);
  const std::vector<int> mine = frames_of_shard(requested, shard);
  std::vector<int> to_shade;
  for (const int frame : mine)
    if (sequence.overwrite || !files.done(outputs, frame)) to_shade.push_back(frame);
  if (!mine.empty()) files.outputs_of(outputs, mine.front()).check_destinations();

  std::cout << "phongcl shade: " << requested.size() << " frames (" << frame_span(requested) << ") of "
            << (inputs.gbuffer_file.empty() ? files.scene.text() : files.gbuffer.text()) << "\n";
  if (shard.count > 1 || !shard_origin.empty())
    std::cout << "  shard      " << shard.index << "/" << shard.count << " (" << shard_origin << "): " << mine.size()
              << " of " << requested.size() << " frames (list positions " << shard.index << ", "
              << shard.index + shard.count << ", ...)\n";
  if (mine.size() > to_shade.size())
    std::cout << "  skipped    " << mine.size() - to_shade.size()
              << " frames whose outputs exist (--overwrite shades them again)\n";
  std::cout.flush();
  if (to_shade.empty()) {
    std::cout << "  nothing to shade\n";
    return;
  }

  sequence.start_exr_threads();
  Relighter relighter(options);  // one device, kernel cache and set of device buffers for every frame
  std::cout << "  device     " << describe(relighter.device()) << "\n";
  // A scene that is not a pattern is the same for every frame: parse it once.
  const std::optional<Scene> shared_scene =
      files.scene.is_pattern() ? std::nullopt : std::optional<Scene>(inputs.load_scene());

  FrameStages stages;
  stages.read = [&](FrameWork& work) {
    const SceneInputs framed = files.inputs_of(inputs, work.frame);
    work.scene = shared_scene ? *shared_scene : framed.load_scene();
    refuse_outputs_over_inputs(framed, files.outputs_of(outputs, work.frame), &work.scene);
    LoadedGBuffer loaded = framed.load_described_gbuffer(work.scene);
    work.gbuffer = std::move(loaded.gbuffer);
    work.layout = std::move(loaded.layout);
  };
  stages.shade = [&](FrameWork& work) {
    work.compression = work.gbuffer.compression;
    relighter.set_frame(work.scene, std::move(work.gbuffer));
    work.image = options.terms ? relighter.shade(work.terms) : relighter.shade();
    work.report = relighter.last_report();
    const ShadeTimings& t = work.report.timings;
    work.times.pack_ms = t.pack_ms + t.upload_ms;
    work.times.kernel_ms = t.kernel_ms;
    work.times.download_ms = t.download_ms;
  };
  stages.write = [&](FrameWork& work) {
    ImageOutputs framed = files.outputs_of(outputs, work.frame);
    framed.compression = sequence.output_compression(work.compression);
    work.written = framed.write(work.image, work.scene.background, work.terms);
  };

  SequenceProgress progress(to_shade.size(), ::isatty(STDOUT_FILENO) == 1);
  const StopOnSignal stop;
  run_frame_pipeline(to_shade, stages, {&stop.requested(), sequence.keep_going},
                     [&](const FrameWork& work) { progress.frame_done(work); });
  progress.finish();

  const double wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  const FrameTimes& t = progress.totals();
  char rate[48];
  std::snprintf(rate, sizeof rate, "%.2f frames/s", static_cast<double>(progress.shaded()) / (wall_ms / 1000.0));
  std::cout << "  frames     " << progress.shaded() << " shaded, " << progress.failed_frames().size() << " failed, "
            << mine.size() - to_shade.size() << " skipped\n"
            << "  time       " << seconds_text(wall_ms) << " wall clock, " << rate << "\n"
            << "  stages     read " << seconds_text(t.read_ms) << ", pack " << seconds_text(t.pack_ms) << ", kernel "
            << seconds_text(t.kernel_ms) << ", download " << seconds_text(t.download_ms) << ", write "
            << seconds_text(t.write_ms) << ", wait " << seconds_text(t.wait_ms)
            << " (summed over frames; read, shading and write overlap)\n";
  if (progress.shaded() > 0)
    std::cout << "  bound by   " << bounding_stage(t) << "\n"
              << "  builds     " << progress.builds() << " program build" << (progress.builds() == 1 ? "" : "s") << ", "
              << milliseconds(progress.build_ms()) << "\n";
  std::string patterns;
  for (const std::string* file : {&outputs.exr_file, &outputs.png_file, &outputs.aov_file})
    if (!file->empty()) patterns += (patterns.empty() ? "" : ", ") + *file;
  if (progress.shaded() > 0) std::cout << "  wrote      " << patterns << "\n";
  std::cout.flush();

  if (stop.requested())
    throw std::runtime_error("stopped by signal " + std::to_string(stop.signal_number()) + " after " +
                             std::to_string(progress.shaded()) + " frames; every output written is whole, run the same command again to shade the rest");
  if (progress.failed_frames().empty()) return;
  if (!sequence.keep_going) throw std::runtime_error(progress.first_failure());
  std::string list;
  for (const int frame : progress.failed_frames()) list += (list.empty() ? "" : ",") + std::to_string(frame);
  throw std::runtime_error(std::to_string(progress.failed_frames().size()) + " frames failed: " + list);
}

}  // namespace phongcl::cli
