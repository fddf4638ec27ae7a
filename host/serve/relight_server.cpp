#include "serve/relight_server.h"

#include <malloc.h>

#include "serve/api_routes.h"
#include "serve/request_framing.h"
#include "serve/web_assets.h"

namespace phongcl {

namespace {

const char* content_type_of(const std::string& name) {
  auto ends_with = [&](std::string_view suffix) { return name.ends_with(suffix); };
  if (ends_with(".html")) return "text/html; charset=utf-8";
  if (ends_with(".js")) return "text/javascript; charset=utf-8";
  if (ends_with(".css")) return "text/css; charset=utf-8";
  if (ends_with(".svg")) return "image/svg+xml";
  return "application/octet-stream";
}

// Requests at least this large are followed by a malloc_trim (RelightServer::answer).
constexpr std::size_t kTrimAfterBytes = 1u << 20;

}  // namespace

RelightServer::RelightServer(LiveRelighter& live, ServeOptions options)
    : live_(live), options_(std::move(options)), api_(std::make_unique<ApiRoutes>(live_, options_)),
      http_(options_.limits, [this](const HttpRequest& request) { return answer(request); }) {
  api_->add_to(router_);
  for (const auto& [name, text] : embedded_web_files()) {
    const std::string path = name == "index.html" ? "/" : "/" + name;
    const std::string body(text);
    const char* type = content_type_of(name);
    router_.add("GET", path, [body, type](const HttpRequest&, HttpResponse& response) {
      response.set_header("Cache-Control", "no-cache");
      response.set_content(body, type);
    });
  }
}

RelightServer::~RelightServer() { stop(); }

int RelightServer::bind() { return http_.bind(options_.host, options_.port); }

void RelightServer::run() { http_.run(); }

void RelightServer::stop() {
  live_.stop();  // first: requests waiting for a frame return, so the workers are free to end
  http_.stop();
}

HttpResponse RelightServer::answer(const HttpRequest& request) {
  HttpResponse response = router_.answer(request);
  // A large body (a scene of many materials) leaves its parse's memory free in this worker's
  // malloc arena, where glibc keeps it: each worker would keep its own, and a server's memory
  // only grow. It goes back to the system now.
  if (request.body.size() >= kTrimAfterBytes) ::malloc_trim(0);
  return response;
}

std::optional<std::string> RelightServer::answer(std::string_view request_bytes) {
  return answer_bytes(request_bytes, options_.limits, [this](const HttpRequest& request) { return answer(request); });
}

ConnectionCounters RelightServer::counters() const { return http_.counters(); }

}  // namespace phongcl
