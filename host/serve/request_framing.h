#pragma once
// Where a request ends, read from its head before it is handed to the HTTP library: the connection
// room buffers a whole request (head and body) before a worker sees it, and refuses at once what
// no endpoint reads.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "serve/http_limits.h"

namespace phongcl {

struct RequestFraming {
  enum class State { incomplete, complete, refused };
  State state = State::incomplete;
  std::size_t head_bytes = 0;  // the request line and headers, with the blank line after them
  std::size_t body_bytes = 0;  // Content-Length
  bool expects_continue = false;  // "Expect: 100-continue": the client waits for an interim 100
  struct Line {
    std::size_t begin, end;  // a header line, with its line break
  };
  // Header lines the library must not see: Expect (the room answers 100-continue; the library
  // would send a second interim 100, or one for a value it URL-decodes to that) and Range (every
  // response is whole, as RFC 9110 allows; the library would cut an error's JSON body down to the
  // range asked for).
  std::vector<Line> unread_lines;
  int status = 0;              // refused: 400, 411, 413, 415 or 431
  std::string error;           // refused: why, in one line
  std::size_t total() const { return head_bytes + body_bytes; }
};

// `input` is what a connection has received of its next request (it may hold more after it).
// complete once head and body are in; refused for a head over max_head_bytes (431), a malformed
// or repeated Content-Length (400), a chunked or otherwise encoded body (411), a body over
// max_body_bytes (413), or a form-encoded body (415: every endpoint reads JSON).
RequestFraming frame_request(std::string_view input, const HttpLimits& limits);

// Takes a complete request off the front of `input`, without its unread header lines.
std::string take_request(std::string& input, const RequestFraming& framing);

// A whole response with a JSON body {"error": message}, for the room's own refusals. `close`
// adds "Connection: close".
std::string error_response(int status, const std::string& message, bool close);

}  // namespace phongcl
