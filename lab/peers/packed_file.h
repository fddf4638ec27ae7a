#pragma once
// The peers' packed input as one binary file, so a peer in another process (the Halide peer, whose
// LLVM cannot share a process with PoCL's) shades exactly the frame and scene the others do.
#include <filesystem>

#include "peers/packed_frame.h"

namespace phongcl {

struct PackedInputs {
  PackedFrame frame;
  PackedScene scene;
};

// Native byte order: writer and reader are the same build on the same machine.
void write_packed_inputs(const std::filesystem::path& file, const PackedFrame& frame, const PackedScene& scene);
// Throws InputError naming the file for a wrong magic, a truncated file or inconsistent plane sizes.
PackedInputs read_packed_inputs(const std::filesystem::path& file);

}  // namespace phongcl
