#pragma once
// Ctrl-C (SIGINT) and a scheduler's SIGTERM (Slurm's scancel and time limit) ask a sequence to stop
// after the frames in flight: while an instance lives, the first such signal only sets a flag; a
// second one ends the process at once, as without the instance.
#include <atomic>

namespace phongcl {

class StopOnSignal {
 public:
  StopOnSignal();
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  const std::atomic<bool>& requested() const;
  int signal_number() const;  // the signal that asked, 0 if none
};

}  // namespace phongcl
