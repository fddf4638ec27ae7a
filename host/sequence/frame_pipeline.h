#pragma once
// Three stages on three threads, so frame n+1 is read and frame n-1 written while frame n shades:
// a reader thread, the calling thread (which shades: OpenCL objects stay on the thread that made
// them) and a writer thread, one frame in each hand-over queue at most.
#include <atomic>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "gbuffer/gbuffer.h"
#include "image/image.h"
#include "scene/scene.h"
#include "shading/shade_stats.h"

namespace phongcl {

// Milliseconds each stage spent on one frame. wait: the shading thread idle, waiting for the frame
// to be read or for the writer to take the previous one; it is what shading cannot hide.
struct FrameTimes {
  double read_ms = 0.0, pack_ms = 0.0, kernel_ms = 0.0, download_ms = 0.0, write_ms = 0.0, wait_ms = 0.0;
  FrameTimes& operator+=(const FrameTimes& other);
};

// One frame on its way through the stages, which fill it in turn.
struct FrameWork {
  int frame = 0;
  Scene scene;
  GBuffer gbuffer;      // until shading takes it
  ExrCompression compression = ExrCompression::zip;  // the G-buffer's, which the outputs default to
  std::string layout;   // what was read, for the summary
  Image image;
  TermImages terms;     // with AOV outputs
  ShadeReport report;
  std::string written;  // what was written, for the summary
  FrameTimes times;     // the pipeline times read, shade and write; a stage may refine its split
  std::exception_ptr error;  // set by the stage that threw; later stages pass the frame on untouched
};

struct FrameStages {
  std::function<void(FrameWork&)> read, shade, write;
};

struct PipelineControl {
  const std::atomic<bool>* stop = nullptr;  // when set (a signal), no further frame is read
  bool keep_going = false;                  // false: the first failed frame stops further reads
};

// Runs every frame through read, shade and write, each frame's shade and write skipped once it has
// failed. Frames already read when a stop comes are finished, so every output is whole. on_done
// is called on the writer thread, in frame order, once per frame that was read (failed or not).
void run_frame_pipeline(const std::vector<int>& frames, const FrameStages& stages, const PipelineControl& control,
                        const std::function<void(const FrameWork&)>& on_done);

}  // namespace phongcl
