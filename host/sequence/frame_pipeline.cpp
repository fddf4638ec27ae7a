#include "sequence/frame_pipeline.h"

#include <chrono>
#include <thread>

#include "sequence/bounded_queue.h"

namespace phongcl {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

// Runs one stage on a frame unless an earlier one failed; returns the stage's milliseconds.
double run_stage(const std::function<void(FrameWork&)>& stage, FrameWork& work) {
  if (work.error) return 0.0;
  const auto start = Clock::now();
  try {
    stage(work);
  } catch (...) {
    work.error = std::current_exception();
  }
  return since(start);
}

}  // namespace

FrameTimes& FrameTimes::operator+=(const FrameTimes& other) {
  read_ms += other.read_ms;
  pack_ms += other.pack_ms;
  kernel_ms += other.kernel_ms;
  download_ms += other.download_ms;
  write_ms += other.write_ms;
  wait_ms += other.wait_ms;
  return *this;
}

void run_frame_pipeline(const std::vector<int>& frames, const FrameStages& stages, const PipelineControl& control,
                        const std::function<void(const FrameWork&)>& on_done) {
  BoundedQueue<FrameWork> read_queue(1), write_queue(1);
  std::atomic<bool> failed{false};
  auto stopping = [&] {
    return (control.stop != nullptr && control.stop->load()) || (!control.keep_going && failed.load());
  };

  std::thread reader([&] {
    for (const int frame : frames) {
      if (stopping()) break;
      FrameWork work;
      work.frame = frame;
      work.times.read_ms = run_stage(stages.read, work);
      if (work.error) failed = true;
      read_queue.push(std::move(work));
    }
    read_queue.close();
  });
  std::thread writer([&] {
    while (std::optional<FrameWork> work = write_queue.pop()) {
      work->times.write_ms = run_stage(stages.write, *work);
      if (work->error) failed = true;
      on_done(*work);
    }
  });

  while (true) {
    const auto fetch_start = Clock::now();
    std::optional<FrameWork> work = read_queue.pop();
    if (!work) break;
    const double fetch_wait = since(fetch_start);
    run_stage(stages.shade, *work);  // the stage splits its own time into pack, kernel and download
    if (work->error) failed = true;
    const auto hand_over_start = Clock::now();
    write_queue.wait_for_room();
    work->times.wait_ms = fetch_wait + since(hand_over_start);
    write_queue.push(std::move(*work));
  }
  write_queue.close();
  reader.join();
  writer.join();
}

}  // namespace phongcl
