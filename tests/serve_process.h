#pragma once
// The real phongcl binary running `serve`, started in the source tree and read until it prints its
// URL, for tests of what only a process shows: its output, its exit on a signal.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>
#include <thread>

#include "cli_runner.h"
#include "temp_dir.h"

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
    for (int i = 0; i < 1200 && output().find("url ") == std::string::npos; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
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
  // Sends `signal` and returns the wait status.
  int stop(int signal) {
    kill(pid_, signal);
    int status = 0;
    waitpid(pid_, &status, 0);
    stopped_ = true;
    return status;
  }
  // Sends `signal` and returns the wait status if the process ends within `limit`; else kills it
  // (SIGKILL) and returns nothing.
  std::optional<int> stop_within(int signal, std::chrono::milliseconds limit) {
    kill(pid_, signal);
    const auto deadline = std::chrono::steady_clock::now() + limit;
    int status = 0;
    while (waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() >= deadline) {
        stop(SIGKILL);
        return std::nullopt;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    stopped_ = true;
    return status;
  }

 private:
  TempDir dir_;
  pid_t pid_ = -1;
  bool stopped_ = false;
};

}  // namespace phongcl::testing
