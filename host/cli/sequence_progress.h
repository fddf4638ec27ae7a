#pragma once
// What a sequence prints while it runs: on a terminal one bar (frames done/total, frames/s, ETA, the
// current frame), elsewhere (CI, a farm's log) one plain line per frame with its time split.
#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "sequence/frame_pipeline.h"

namespace phongcl::cli {

class SequenceProgress {
 public:
  SequenceProgress(std::size_t total, bool terminal);

  // Called once per frame, from the pipeline's writer thread only.
  void frame_done(const FrameWork& work);
  // Clears the bar; then the totals below are final.
  void finish();

  std::size_t shaded() const { return shaded_; }
  const std::vector<int>& failed_frames() const { return failed_; }
  const std::string& first_failure() const { return first_failure_; }
  const FrameTimes& totals() const { return totals_; }
  std::size_t builds() const { return builds_; }
  double build_ms() const { return build_ms_; }

 private:
  void draw_bar(int frame);

  std::size_t total_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::size_t shaded_ = 0, builds_ = 0;
  double build_ms_ = 0.0;
  std::vector<int> failed_;
  std::string first_failure_;
  FrameTimes totals_;
};

// "read 210 ms, pack 20.1 ms, kernel 35.2 ms, download 9.80 ms, write 301 ms, wait 0.51 ms"
std::string describe_split(const FrameTimes& times);
// The stage that took longest: what bounds the run.
std::string bounding_stage(const FrameTimes& totals);
// The message of the exception a frame failed with, prefixed by the frame ("frame 1003: ...").
std::string failure_message(const FrameWork& work);

}  // namespace phongcl::cli
