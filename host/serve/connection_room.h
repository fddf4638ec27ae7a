#pragma once
// Every connection of the server between requests. One thread polls them all: it reads each
// request whole (head and body, within HttpLimits' times and sizes) before a worker sees it, and
// writes each response out as fast as the client takes it. Workers only run handlers, so a client
// that sends slowly, reads slowly or stays idle holds a socket and a buffer, never a thread.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "serve/http_limits.h"

namespace phongcl {

// One request as a worker answers it.
struct Exchange {
  std::string request;   // exactly one request, head and body
  std::string response;  // the whole response, appended by the worker
  bool close = false;    // set by the worker: close the connection after the response
  std::string remote_ip, local_ip;
  int remote_port = -1, local_port = -1;
};

// What the room has done so far, for /api/stats and the slow-client check.
struct RoomCounters {
  std::uint64_t connections = 0;  // admitted
  std::uint64_t requests = 0;     // handed to a worker
  std::uint64_t refused = 0;      // answered by the room itself (4xx, 503)
  std::uint64_t timed_out = 0;    // closed at a deadline: idle, request or response too slow
  std::uint64_t evicted = 0;      // closed to make room (connections or buffered bytes over the limit)
  std::size_t open = 0;           // connections open now
};

class ConnectionRoom {
 public:
  // `answer` runs on a worker for each complete request and must not throw.
  ConnectionRoom(const HttpLimits& limits, std::function<void(Exchange&)> answer);
  ~ConnectionRoom();
  ConnectionRoom(const ConnectionRoom&) = delete;
  ConnectionRoom& operator=(const ConnectionRoom&) = delete;

  // Takes a connected socket (and closes it when done). Any thread.
  void admit(int socket);
  // Takes no more connections or requests; responses in flight get HttpLimits::stop_time to be
  // written, then every connection closes. Any thread, idempotent; join() waits for the end.
  void stop();
  void join();
  RoomCounters counters() const;

 private:
  struct Connection;
  struct Finished {
    std::uint64_t id;
    Exchange exchange;
  };
  void poll_loop();
  void work_loop();
  void wake();

  const HttpLimits limits_;
  const std::function<void(Exchange&)> answer_;
  int wake_fd_ = -1;  // an eventfd: admissions, finished exchanges and stop() interrupt poll()

  mutable std::mutex mutex_;
  std::condition_variable work_ready_;
  // Guarded by mutex_:
  std::vector<int> admitted_;
  std::deque<Finished> to_answer_, answered_;
  bool stopping_ = false;
  RoomCounters counters_;

  std::vector<std::thread> workers_;
  std::thread poller_;  // last: starts after everything above exists
};

}  // namespace phongcl
