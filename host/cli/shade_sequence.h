#pragma once
// shade's sequence mode (frame patterns in --scene/--gbuffer/--out/--png/--aov, or --frames) and the
// EXR options both modes share (--threads, --compression).
#include <string>

#include <CLI/CLI.hpp>

#include "cli/inputs.h"
#include "cli/outputs.h"

namespace phongcl {
struct RelighterOptions;
}

namespace phongcl::cli {

struct SequenceOptions {
  std::string frames;       // "1001-1240", "1001,1010-1020x2"; empty: the frames found on disk
  std::string shard;        // "I/N"; empty: from a Slurm job array, else every frame
  bool overwrite = false;   // shade frames whose outputs exist
  bool keep_going = false;  // a failed frame does not stop the others
  int threads = 0;          // OpenEXR (de)compression threads; 0: every core
  std::string compression;  // of the EXRs written; empty: the input's

  void add_options(CLI::App& command);
  // Any pattern, or --frames: shade is a sequence.
  bool wanted(const SceneInputs& inputs, const ImageOutputs& outputs) const;
  // Starts OpenEXR's thread pool with --threads (every core by default).
  void start_exr_threads() const;
  // --compression, else the input G-buffer's.
  ExrCompression output_compression(ExrCompression input) const;
};

// Shades every frame of the sequence, skipping those already done; prints progress and a summary.
// Throws (after the summary) when a frame failed or a signal stopped the run.
void run_shade_sequence(const SceneInputs& inputs, const ImageOutputs& outputs, const RelighterOptions& options,
                        const SequenceOptions& sequence);

}  // namespace phongcl::cli
