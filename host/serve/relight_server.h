#pragma once
// `phongcl serve`'s HTTP server: the page (web/, embedded) and the JSON/image API over a
// LiveRelighter. docs/serve.md "HTTP API" lists the endpoints; serve/http_limits.h says
// what one client may hold.
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "serve/http_limits.h"
#include "serve/http_router.h"
#include "serve/http_server.h"
#include "serve/live_relighter.h"

namespace phongcl {

class ApiRoutes;

struct ServeOptions {
  std::string host = "127.0.0.1";
  int port = 8080;                  // 0: any free port (bind() says which)
  std::filesystem::path save_path;  // POST /api/save writes the scene here; empty: refused
  std::string device;               // the device's description, for /api/stats
  HttpLimits limits;
  // The longest a request waits for a frame: an image of the state not yet shaded (the first
  // frame can include a kernel build of several seconds on a busy machine), a long poll.
  std::chrono::milliseconds frame_timeout{120'000}, max_poll{60'000};
};

class RelightServer {
 public:
  RelightServer(LiveRelighter& live, ServeOptions options);
  ~RelightServer();
  // Binds the listening socket; returns the port. Throws std::runtime_error when it cannot.
  int bind();
  // Serves until stop(); call bind() first. Returns once every connection is closed: at most
  // HttpLimits::stop_time after stop() for responses in flight.
  void run();
  // Wakes waiting requests and makes run() return; safe from any thread, idempotent.
  void stop();
  // One request's bytes to its response's, as a connection would answer them, without a socket:
  // the HTTP fuzzer's way in. Nothing while the bytes are not a whole request. Never throws.
  std::optional<std::string> answer(std::string_view request_bytes);
  ConnectionCounters counters() const;

 private:
  HttpResponse answer(const HttpRequest& request);

  LiveRelighter& live_;
  ServeOptions options_;
  std::unique_ptr<ApiRoutes> api_;
  HttpRouter router_;
  HttpServer http_;
};

}  // namespace phongcl
