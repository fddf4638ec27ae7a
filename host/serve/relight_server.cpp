#include "serve/relight_server.h"

#include <httplib.h>
#include <malloc.h>
#include <sys/socket.h>

#include <stdexcept>

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

// Requests at least this large are followed by a malloc_trim (RoutedServer::answer).
constexpr std::size_t kTrimAfterBytes = 1u << 20;

// httplib's accept loop hands each connection to a task queue; this one passes it on at once, on
// the accept thread, to the connection room (which never blocks on a client).
class HandOver : public httplib::TaskQueue {
 public:
  void enqueue(std::function<void()> hand_over) override { hand_over(); }
  void shutdown() override {}
};

// A request's bytes as the room received them, and its response gathered for the room to write.
class ExchangeStream : public httplib::Stream {
 public:
  explicit ExchangeStream(Exchange& exchange) : exchange_(exchange) {}
  bool is_readable() const override { return read_ < exchange_.request.size(); }
  bool is_writable() const override { return true; }
  ssize_t read(char* bytes, size_t size) override {
    const std::size_t count = std::min(size, exchange_.request.size() - read_);
    exchange_.request.copy(bytes, count, read_);
    read_ += count;
    return static_cast<ssize_t>(count);
  }
  ssize_t write(const char* bytes, size_t size) override {
    exchange_.response.append(bytes, size);
    return static_cast<ssize_t>(size);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = exchange_.remote_ip;
    port = exchange_.remote_port;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip = exchange_.local_ip;
    port = exchange_.local_port;
  }
  socket_t socket() const override { return INVALID_SOCKET; }  // none: the room owns it

 private:
  Exchange& exchange_;
  std::size_t read_ = 0;
};

}  // namespace

// httplib's router and request parser, fed by the connection room: the accept loop's sockets go
// to the room (process_and_close_socket, the library's hook for how a connection is served, as
// its SSLServer uses it), and the room's workers run answer() on whole requests.
class RoutedServer : public httplib::Server {
 public:
  explicit RoutedServer(const HttpLimits& limits) : room_(limits, [this](Exchange& exchange) { answer(exchange); }) {
    new_task_queue = [] { return new HandOver; };
  }

  void answer(Exchange& exchange) {
    ExchangeStream stream(exchange);
    bool closed = false;
    try {
      exchange.close = !process_request(stream, false, closed, nullptr) || closed;
    } catch (...) {  // the library's own failure (the handlers catch theirs): this request ends, the server goes on
      exchange.response = error_response(500, "internal error while answering the request", true);
      exchange.close = true;
    }
    // A large body (a scene of many materials) leaves its parse's memory free in this worker's
    // malloc arena, where glibc keeps it: each worker would keep its own, and a server's memory
    // only grow. It goes back to the system now.
    if (exchange.request.size() >= kTrimAfterBytes) ::malloc_trim(0);
  }

  // httplib listens with a backlog of 5: a burst of connections beyond it (a page opens six, a
  // script more) waits for the client's SYN retransmission, a second. Listening again on the
  // bound socket raises it.
  void widen_backlog() { ::listen(svr_sock_, SOMAXCONN); }

  void stop_all() {
    stop();
    room_.stop();
  }
  void join() { room_.join(); }
  RoomCounters counters() const { return room_.counters(); }

 private:
  bool process_and_close_socket(socket_t socket) override {
    room_.admit(socket);
    return true;
  }

  ConnectionRoom room_;
};

RelightServer::RelightServer(LiveRelighter& live, ServeOptions options)
    : live_(live), options_(std::move(options)), api_(std::make_unique<ApiRoutes>(live_, options_)),
      http_(std::make_unique<RoutedServer>(options_.limits)) {
  http_->set_payload_max_length(options_.limits.max_body_bytes);
  // httplib writes a response's headers and body separately: with Nagle's algorithm the body waits
  // for the client's delayed ACK of the headers, tens of milliseconds a frame. (The room writes
  // whole responses, and sets it on every connection too.)
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

RelightServer::~RelightServer() {
  stop();
  http_->join();
}

int RelightServer::bind() {
  const int port = options_.port == 0 ? http_->bind_to_any_port(options_.host)
                                      : (http_->bind_to_port(options_.host, options_.port) ? options_.port : -1);
  if (port < 0)
    throw std::runtime_error("cannot listen on " + options_.host + ":" + std::to_string(options_.port) +
                             " (in use, or not an address of this machine)");
  http_->widen_backlog();
  return port;
}

void RelightServer::run() {
  http_->listen_after_bind();
  stop();  // as asked, or the listening socket failed: either way no connection is left open
  http_->join();
}

void RelightServer::stop() {
  live_.stop();  // first: requests waiting for a frame return, so the workers are free to end
  http_->stop_all();
}

void RelightServer::answer(Exchange& exchange) { http_->answer(exchange); }

RoomCounters RelightServer::counters() const { return http_->counters(); }

}  // namespace phongcl
