#pragma once
// `phongcl serve`'s HTTP server: the page (web/, embedded) and the JSON/image API over a
// LiveRelighter. docs/serve.md "HTTP API" lists the endpoints.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

#include "serve/live_relighter.h"

namespace httplib {
class Server;
}

namespace phongcl {

class ApiRoutes;

struct ServeOptions {
  std::string host = "127.0.0.1";
  int port = 8080;                  // 0: any free port (bind() says which)
  std::filesystem::path save_path;  // POST /api/save writes the scene here; empty: refused
  std::string device;               // the device's description, for /api/stats
};

// Request bodies larger than this are refused with 413: a scene file is kilobytes.
inline constexpr std::size_t kMaxRequestBytes = 8u << 20;

class RelightServer {
 public:
  RelightServer(LiveRelighter& live, ServeOptions options);
  ~RelightServer();
  // Binds the listening socket; returns the port. Throws std::runtime_error when it cannot.
  int bind();
  // Serves until stop(); call bind() first.
  void run();
  // Wakes waiting requests and makes run() return; safe from any thread, idempotent.
  void stop();

 private:
  LiveRelighter& live_;
  ServeOptions options_;
  std::unique_ptr<httplib::Server> http_;
  std::unique_ptr<ApiRoutes> api_;
};

}  // namespace phongcl
