#include "sequence/stop_signal.h"

#include <csignal>

namespace phongcl {

namespace {

std::atomic<bool> stop_requested{false};
std::atomic<int> stop_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "a signal handler may only touch lock-free atomics");

struct sigaction previous_int, previous_term;

extern "C" void on_stop_signal(int number) {
  if (stop_requested.exchange(true)) {
    std::signal(number, SIG_DFL);  // the second signal: stop now
    std::raise(number);
    return;
  }
  stop_signal = number;
}

}  // namespace

StopOnSignal::StopOnSignal() {
  stop_requested = false;
  stop_signal = 0;
  struct sigaction action = {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
}

StopOnSignal::~StopOnSignal() {
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
}

const std::atomic<bool>& StopOnSignal::requested() const { return stop_requested; }
int StopOnSignal::signal_number() const { return stop_signal; }

}  // namespace phongcl
