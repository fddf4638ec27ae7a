#include "serve/relight_server.h"

#include <httplib.h>

#include <stdexcept>

#include "serve/api_routes.h"
#include "serve/web_assets.h"

namespace phongcl {

namespace {

// Enough for two tabs' keep-alive connections (a browser opens up to six each), their long polls
// and a script, so that no request waits for a free thread.
constexpr std::size_t kServerThreads = 32;

const char* content_type_of(const std::string& name) {
  auto ends_with = [&](std::string_view suffix) { return name.ends_with(suffix); };
  if (ends_with(".html")) return "text/html; charset=utf-8";
  if (ends_with(".js")) return "text/javascript; charset=utf-8";
  if (ends_with(".css")) return "text/css; charset=utf-8";
  if (ends_with(".svg")) return "image/svg+xml";
  return "application/octet-stream";
}

// httplib answers some errors itself with an empty body (404 no route, 413 too large, 400
// unparsable request); every error the API sends carries {"error": ...} already.
std::string default_error_message(const httplib::Request& request, int status) {
  switch (status) {
    case 404: return "not found: " + request.method + " " + request.path;
    case 413: return "request too large (the limit is " + std::to_string(kMaxRequestBytes >> 20) + " MiB)";
    case 400: return "malformed HTTP request";
    default: return "HTTP error " + std::to_string(status);
  }
}

}  // namespace

RelightServer::RelightServer(LiveRelighter& live, ServeOptions options)
    : live_(live), options_(std::move(options)), http_(std::make_unique<httplib::Server>()),
      api_(std::make_unique<ApiRoutes>(live_, options_)) {
  http_->new_task_queue = [] { return new httplib::ThreadPool(kServerThreads); };
  http_->set_payload_max_length(kMaxRequestBytes);
  http_->set_keep_alive_timeout(2);
  // httplib writes a response's headers and body separately: with Nagle's algorithm the body waits
  // for the client's delayed ACK of the headers, tens of milliseconds a frame.
  http_->set_tcp_nodelay(true);
  api_->add_to(*http_);
  for (const auto& [name, text] : embedded_web_files()) {
    const std::string path = name == "index.html" ? "/" : "/" + name;
    const std::string body(text);
    const char* type = content_type_of(name);
    http_->Get(path, [body, type](const httplib::Request&, httplib::Response& response) {
      response.set_header("Cache-Control", "no-cache");
      response.set_content(body, type);
    });
  }
  http_->set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request& request,
                                                                     httplib::Response& response) {
    if (!response.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    response.set_content(error_json(default_error_message(request, response.status)), "application/json");
    return httplib::Server::HandlerResponse::Handled;
  }));
  http_->set_exception_handler([](const httplib::Request&, httplib::Response& response, std::exception_ptr error) {
    std::string message = "internal error";
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      message = e.what();
    } catch (...) {
    }
    response.status = 500;
    response.set_content(error_json(message), "application/json");
  });
}

RelightServer::~RelightServer() { stop(); }

int RelightServer::bind() {
  const int port = options_.port == 0 ? http_->bind_to_any_port(options_.host)
                                      : (http_->bind_to_port(options_.host, options_.port) ? options_.port : -1);
  if (port < 0)
    throw std::runtime_error("cannot listen on " + options_.host + ":" + std::to_string(options_.port) +
                             " (in use, or not an address of this machine)");
  return port;
}

void RelightServer::run() { http_->listen_after_bind(); }

void RelightServer::stop() {
  live_.stop();  // first: long polls waiting for a frame return, so the server's threads can end
  http_->stop();
}

}  // namespace phongcl
