#pragma once
// Waiting in a test with a deadline. The limits only end a hang: a bug then fails its test within a
// minute instead of holding ctest for its 600 s timeout, so they are generous; a test that bounds how
// long something may take asserts that itself.
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <optional>
#include <thread>

namespace phongcl::testing {

inline constexpr std::chrono::seconds kHangLimit{60};

// True as soon as `holds()` is, false if it still is not after `limit`.
template <typename Condition>
bool wait_until(Condition holds, std::chrono::milliseconds limit = kHangLimit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!holds()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

// Reaps the child process `pid`: its wait status, or nothing if it still runs after `limit`, when it
// is killed (SIGKILL, which it cannot ignore) and reaped.
inline std::optional<int> wait_for_child(pid_t pid, std::chrono::milliseconds limit = kHangLimit) {
  int status = 0;
  if (wait_until([&] { return ::waitpid(pid, &status, WNOHANG) != 0; }, limit)) return status;
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return std::nullopt;
}

}  // namespace phongcl::testing
