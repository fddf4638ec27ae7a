#include "serve/http_server.h"

#include <array>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <vector>

#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/write.hpp>

namespace phongcl {

namespace {

namespace net = boost::asio;
namespace http = boost::beast::http;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;
using boost::beast::error_code;

// An idle connection holds a buffer of this size for the first bytes of its next request.
constexpr std::size_t kFirstRead = 1024;
// After a response that ends the connection, what the client still sends (the rest of a refused
// body) is read and dropped for this long before closing: closing with unread bytes would reset
// the connection, and the client could lose the response.
constexpr std::chrono::milliseconds kLinger{2000};
constexpr std::string_view kContinue = "HTTP/1.1 100 Continue\r\n\r\n";

}  // namespace

// One client's connection, request after request. Every step runs on the I/O thread but the
// answer, which a worker computes.
class HttpServer::Connection : public std::enable_shared_from_this<Connection> {
 public:
  enum class State { idle, reading, working, writing, lingering, closed };

  Connection(HttpServer& server, std::uint64_t id, tcp::socket socket)
      : server_(server), id_(id), socket_(std::move(socket)), deadline_(server.io_) {}

  State state() const { return state_; }
  Clock::time_point since() const { return since_; }

  void wait_for_request() {
    if (server_.stopping_) return close();
    if (buffer_.size() > 0) return read_head();  // a request sent behind the last one
    buffer_.shrink_to_fit();  // what the last request's head took goes back while the client idles
    enter(State::idle, server_.limits_.idle);
    auto on_read = [self = shared_from_this()](error_code error, std::size_t size) {
      if (self->state_ != State::idle) return;
      if (error) return self->close();
      self->buffer_.commit(size);
      self->read_head();
    };
    socket_.async_read_some(buffer_.prepare(kFirstRead), std::move(on_read));
  }

  // Answers with `response` (the server's own refusal), then closes.
  void refuse(HttpResponse response) {
    server_.count([](ConnectionCounters& c) { ++c.refused; });
    write(std::move(response), false, false);
  }

  void close() {
    if (state_ == State::closed) return;
    const auto keep = shared_from_this();  // the server forgets it below
    state_ = State::closed;
    server_.release_bytes(held_);
    held_ = 0;
    deadline_.cancel();
    error_code ignored;
    socket_.close(ignored);
    server_.forget(id_);
  }

 private:
  // The deadline of each state: idle connections close, a request too slow to arrive gets 408, a
  // response too slow to be taken is abandoned.
  void enter(State state, std::chrono::milliseconds limit) {
    state_ = state;
    since_ = Clock::now();
    expired_ = false;
    deadline_.expires_after(limit);
    deadline_.async_wait([self = shared_from_this(), generation = ++generation_](error_code error) {
      if (!error && generation == self->generation_) self->on_deadline();
    });
  }

  void on_deadline() {
    if (state_ == State::lingering) return close();
    server_.count([](ConnectionCounters& c) { ++c.timed_out; });
    if (state_ != State::reading) return close();
    expired_ = true;
    error_code ignored;
    socket_.cancel(ignored);  // the read ends with operation_aborted, then 408
  }

  void read_head() {
    enter(State::reading, server_.limits_.request_time);
    parser_.emplace();
    hold_to_limits(*parser_, server_.limits_);
    http::async_read_header(socket_, buffer_, *parser_, [self = shared_from_this()](error_code error, std::size_t) {
      if (error) return self->on_read_error(error);
      if (auto refusal = refusal_for_head(*self->parser_)) return self->refuse(std::move(*refusal));
      if (!self->hold_request_body()) return;
      if (!expects_continue(*self->parser_) || self->parser_->is_done()) return self->read_body();
      net::async_write(self->socket_, net::buffer(kContinue.data(), kContinue.size()),
                       [self](error_code error, std::size_t) {
                         error ? self->on_read_error(error) : self->read_body();
                       });
    });
  }

  // The body's bytes count with the server's buffered bytes from here until its response is
  // written; over the limit the request gets 503 before its body is read.
  bool hold_request_body() {
    const std::size_t bytes = parser_->content_length().value_or(0);
    if (server_.buffered_ + bytes > server_.limits_.max_buffered_bytes) {
      refuse(error_response(503, "the server holds too many bytes for other clients: try again"));
      return false;
    }
    held_ = bytes;
    server_.buffered_ += bytes;
    return true;
  }

  void read_body() {
    if (parser_->is_done()) return dispatch();
    http::async_read(socket_, buffer_, *parser_, [self = shared_from_this()](error_code error, std::size_t) {
      error ? self->on_read_error(error) : self->dispatch();
    });
  }

  void on_read_error(error_code error) {
    if (state_ != State::reading) return;
    if (expired_)
      return refuse(error_response(408, "request not received within " +
                                            std::to_string(server_.limits_.request_time.count()) + " ms"));
    if (auto refusal = refusal_for(error, server_.limits_)) return refuse(std::move(*refusal));
    close();
  }

  // The whole request to a worker; its answer back to this thread to be written.
  void dispatch() {
    state_ = State::working;
    since_ = Clock::now();
    deadline_.cancel();
    server_.count([](ConnectionCounters& c) { ++c.requests; });
    const bool head = parser_->get().method() == http::verb::head, keep_alive = parser_->get().keep_alive();
    net::post(server_.workers_, [self = shared_from_this(), request = request_of(*parser_), head, keep_alive] {
      HttpResponse response = self->server_.answer_(request);
      net::post(self->server_.io_, [self, response = std::move(response), head, keep_alive]() mutable {
        self->write(std::move(response), head, keep_alive);
      });
    });
    parser_.reset();
  }

  void write(HttpResponse response, bool head, bool keep_alive) {
    if (state_ == State::closed) return;
    keep_alive_ = keep_alive && !server_.stopping_;
    response_ = wire_response(std::move(response), head, keep_alive_);
    enter(State::writing, server_.limits_.write_time);
    server_.release_bytes(held_);
    held_ = response_.body().size();
    server_.hold_bytes(id_, held_);
    http::async_write(socket_, response_, [self = shared_from_this()](error_code error, std::size_t) {
      if (self->state_ != State::writing) return;
      self->server_.release_bytes(self->held_);
      self->held_ = 0;
      self->response_ = {};  // a large response's memory goes back now, not at the next one
      if (error || self->server_.stopping_) return self->close();
      self->keep_alive_ ? self->wait_for_request() : self->linger();
    });
  }

  void linger() {
    error_code ignored;
    socket_.shutdown(tcp::socket::shutdown_send, ignored);
    enter(State::lingering, kLinger);
    drain();
  }

  void drain() {
    socket_.async_read_some(net::buffer(discard_), [self = shared_from_this()](error_code error, std::size_t) {
      if (self->state_ != State::lingering) return;
      error ? self->close() : self->drain();
    });
  }

  HttpServer& server_;
  const std::uint64_t id_;
  tcp::socket socket_;
  net::steady_timer deadline_;
  std::uint64_t generation_ = 0;  // of the deadline: a wait that is not the latest's does nothing
  boost::beast::flat_buffer buffer_;
  std::optional<RequestParser> parser_;
  WireResponse response_;
  std::size_t held_ = 0;  // this request's body or response, counted in the server's buffered bytes
  State state_ = State::idle;
  Clock::time_point since_ = Clock::now();
  bool expired_ = false;  // the reading deadline passed
  bool keep_alive_ = false;
  std::array<char, 4096> discard_{};
};

HttpServer::HttpServer(const HttpLimits& limits, Answer answer)
    : limits_(limits), answer_(std::move(answer)), workers_(limits.workers) {}

HttpServer::~HttpServer() {
  stop();
  workers_.stop();
  workers_.join();
}

int HttpServer::bind(const std::string& host, int port) {
  error_code error;
  const auto endpoints = tcp::resolver(io_).resolve(host, std::to_string(port), tcp::resolver::passive, error);
  for (const auto& entry : endpoints) {
    acceptor_.close(error);
    acceptor_.open(entry.endpoint().protocol(), error);
    if (!error) acceptor_.set_option(tcp::acceptor::reuse_address(true), error);
    if (!error) acceptor_.bind(entry.endpoint(), error);
    if (!error) acceptor_.listen(net::socket_base::max_listen_connections, error);
    if (!error) return acceptor_.local_endpoint().port();
  }
  acceptor_.close(error);
  throw std::runtime_error("cannot listen on " + host + ":" + std::to_string(port) +
                           " (in use, or not an address of this machine)");
}

void HttpServer::run() {
  accept();
  io_.run();
  workers_.stop();  // requests not yet begun have no connection left to answer
  workers_.join();
}

void HttpServer::stop() {
  net::post(io_, [this] { begin_stop(); });
}

ConnectionCounters HttpServer::counters() const {
  std::lock_guard lock(counters_mutex_);
  return counters_;
}

template <typename Change>
void HttpServer::count(Change change) {
  std::lock_guard lock(counters_mutex_);
  change(counters_);
  counters_.open = connections_.size();
}

void HttpServer::accept() {
  acceptor_.async_accept([this](error_code error, tcp::socket socket) {
    if (!acceptor_.is_open()) return;
    if (!error) admit(std::move(socket));
    accept();
  });
}

void HttpServer::admit(tcp::socket socket) {
  if (stopping_) return;
  error_code ignored;
  // Beast writes a response's head and body in one go; without this a small response can still
  // wait for the client's delayed ACK of the one before it.
  socket.set_option(tcp::no_delay(true), ignored);
  std::optional<HttpResponse> busy;
  if (connections_.size() >= limits_.max_connections) {
    // Room for the newcomer: the connection idle longest goes; with none idle, the newcomer.
    std::shared_ptr<Connection> oldest;
    for (const auto& [id, c] : connections_)
      if (c->state() == Connection::State::idle && (!oldest || c->since() < oldest->since())) oldest = c;
    if (oldest) {
      oldest->close();
      count([](ConnectionCounters& c) { ++c.evicted; });
    } else {
      busy = error_response(503, "too many connections (" + std::to_string(limits_.max_connections) + "): try again");
    }
  }
  const std::uint64_t id = next_id_++;
  auto connection = std::make_shared<Connection>(*this, id, std::move(socket));
  connections_.emplace(id, connection);
  count([](ConnectionCounters& c) { ++c.connections; });
  busy ? connection->refuse(std::move(*busy)) : connection->wait_for_request();
}

void HttpServer::forget(std::uint64_t id) {
  connections_.erase(id);
  count([](ConnectionCounters&) {});
  if (stopping_ && connections_.empty()) stop_timer_.cancel();
}

void HttpServer::hold_bytes(std::uint64_t id, std::size_t bytes) {
  buffered_ += bytes;
  while (buffered_ > limits_.max_buffered_bytes) {
    std::shared_ptr<Connection> slowest;
    for (const auto& [other_id, c] : connections_)
      if (other_id != id && c->state() == Connection::State::writing && (!slowest || c->since() < slowest->since()))
        slowest = c;
    if (!slowest) break;
    slowest->close();
    count([](ConnectionCounters& c) { ++c.evicted; });
  }
}

void HttpServer::begin_stop() {
  if (stopping_) return;
  stopping_ = true;
  error_code ignored;
  acceptor_.close(ignored);
  // Nothing new is read: connections between requests close now, responses in flight are written.
  std::vector<std::shared_ptr<Connection>> waiting;
  for (const auto& [id, c] : connections_)
    if (c->state() != Connection::State::working && c->state() != Connection::State::writing) waiting.push_back(c);
  for (const auto& c : waiting) c->close();
  if (connections_.empty()) return;
  stop_timer_.expires_after(limits_.stop_time);
  stop_timer_.async_wait([this](error_code error) {
    if (error) return;
    std::vector<std::shared_ptr<Connection>> left;
    for (const auto& [id, c] : connections_) left.push_back(c);
    for (const auto& c : left) c->close();
  });
}

}  // namespace phongcl
