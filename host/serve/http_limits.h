#pragma once
// What one client may hold of `phongcl serve`, stated once (docs/reliability.md quotes them). A
// connection costs a thread only while a complete request is being answered: reading requests and
// writing responses happen on one I/O thread (serve/http_server.h), so clients that send slowly,
// read slowly or stay idle hold a socket and a buffer, never a worker.
#include <chrono>
#include <cstddef>

namespace phongcl {

// Request bodies larger than this are refused with 413: a scene file is kilobytes to megabytes.
inline constexpr std::size_t kMaxRequestBytes = 8u << 20;

struct HttpLimits {
  using milliseconds = std::chrono::milliseconds;
  // Threads that answer complete requests, and how many of them may wait for a frame at once
  // (long polls, images of a state not yet shaded); a request beyond that gets 503. The rest
  // always answer the page and the API at once.
  std::size_t workers = 16;
  std::size_t max_waiting = 8;
  // Open connections; a new one beyond closes the connection idle longest (or gets 503 when none is idle).
  std::size_t max_connections = 512;
  // A request's head and body must arrive within this of its first byte (else 408 and closed);
  // a connection with no request in progress is closed after idle.
  milliseconds request_time{10'000};
  milliseconds idle{5'000};
  // A response must be taken within this, else the connection is closed.
  milliseconds write_time{30'000};
  // Request heads (request line and headers) and bodies above these are refused (431, 413).
  std::size_t max_head_bytes = 64u << 10;
  std::size_t max_body_bytes = kMaxRequestBytes;
  // Bytes held for all connections together (request bodies, responses being written): a request
  // whose body would pass it gets 503, and a response that passes it drops those waiting longest.
  std::size_t max_buffered_bytes = std::size_t{512} << 20;
  // After stop(): responses in flight get this long to be written, then every connection closes.
  milliseconds stop_time{1'500};
};

}  // namespace phongcl
