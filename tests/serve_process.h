#pragma once
// The real phongcl binary running `serve`, started in the source tree and read until it prints its
// URL, for tests of what only a process shows: its output, its exit on a signal.
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>

#include "cli_runner.h"
#include "temp_dir.h"
#include "wait_until.h"

namespace phongcl::testing {

class ServeProcess {
 public:
  explicit ServeProcess(const std::string& arguments) : dir_("serve_cli") {
    const std::string command = "cd '" PHONGCL_SOURCE_DIR "' && exec '" PHONGCL_EXE "' serve " + arguments +
                                " </dev/null >'" + (dir_ / "out.txt").string() + "' 2>&1";
    pid_ = fork();
    if (pid_ == 0) {
      execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    wait_until([this] { return output().find("url ") != std::string::npos; });
  }
  ~ServeProcess() {
    if (pid_ > 0 && !stopped_) stop(SIGKILL);
  }
  ServeProcess(const ServeProcess&) = delete;
  ServeProcess& operator=(const ServeProcess&) = delete;

  std::string output() const { return read_text(dir_ / "out.txt"); }
  int port() const {
    const std::string text = output();
    const std::size_t at = text.find("url        http://");
    return at == std::string::npos ? -1 : std::stoi(text.substr(text.find(':', at + 18) + 1));
  }
  // Sends `signal` and returns the wait status; -1 for a process that still ran after kHangLimit
  // (it is then killed).
  int stop(int signal) { return stop_within(signal, kHangLimit).value_or(-1); }
  // Sends `signal` and returns the wait status if the process ends within `limit`; else kills it
  // (SIGKILL) and returns nothing.
  std::optional<int> stop_within(int signal, std::chrono::milliseconds limit) {
    kill(pid_, signal);
    stopped_ = true;
    return wait_for_child(pid_, limit);
  }

 private:
  TempDir dir_;
  pid_t pid_ = -1;
  bool stopped_ = false;
};

}  // namespace phongcl::testing
