#pragma once
// The server's connections, on Boost.Asio with Boost.Beast's parser. One I/O thread reads every
// request whole (head and body, within HttpLimits' times and sizes) before a worker sees it, and
// writes every response as fast as the client takes it; workers only run the answer. A client that
// sends slowly, reads slowly or stays idle holds a socket and a buffer, never a thread.
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/thread_pool.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "serve/http_limits.h"
#include "serve/request_framing.h"

namespace phongcl {

// What the server has done so far, for the slow-client checks.
struct ConnectionCounters {
  std::uint64_t connections = 0;  // admitted
  std::uint64_t requests = 0;     // handed to a worker
  std::uint64_t refused = 0;      // answered by the server itself (4xx, 503)
  std::uint64_t timed_out = 0;    // closed at a deadline: idle, request or response too slow
  std::uint64_t evicted = 0;      // closed to make room (connections or buffered bytes over the limit)
  std::size_t open = 0;           // connections open now
};

class HttpServer {
 public:
  // `answer` runs on a worker for each complete request and must not throw.
  HttpServer(const HttpLimits& limits, Answer answer);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Listens on host:port (0: any free port); returns the port. Throws std::runtime_error when it cannot.
  int bind(const std::string& host, int port);
  // Serves until stop(); returns once every connection is closed and every worker is done.
  void run();
  // Takes no more connections or requests; responses in flight get HttpLimits::stop_time to be
  // written, then every connection closes. Any thread, idempotent.
  void stop();
  ConnectionCounters counters() const;

 private:
  class Connection;
  friend class Connection;
  void accept();
  void admit(boost::asio::ip::tcp::socket socket);
  void begin_stop();
  void forget(std::uint64_t id);
  // Counts a response's bytes with the rest held (request bodies, responses being written): above
  // the limit, the responses waiting longest are dropped (their connections closed).
  void hold_bytes(std::uint64_t id, std::size_t bytes);
  void release_bytes(std::size_t bytes) { buffered_ -= bytes; }
  template <typename Change>
  void count(Change change);

  const HttpLimits limits_;
  const Answer answer_;
  boost::asio::io_context io_;
  boost::asio::ip::tcp::acceptor acceptor_{io_};
  boost::asio::steady_timer stop_timer_{io_};
  boost::asio::thread_pool workers_;
  // Only on the I/O thread:
  std::map<std::uint64_t, std::shared_ptr<Connection>> connections_;
  std::uint64_t next_id_ = 0;
  std::size_t buffered_ = 0;
  bool stopping_ = false;

  mutable std::mutex counters_mutex_;
  ConnectionCounters counters_;  // guarded by counters_mutex_
};

}  // namespace phongcl
