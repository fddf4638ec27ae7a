#include "serve/connection_room.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <map>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "serve/request_framing.h"

namespace phongcl {

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kReadChunk = 64u << 10;
constexpr std::chrono::milliseconds kLongestPoll{1000};  // deadlines are checked at least this often
// After a response that ends the connection, what the client still sends (the rest of a refused
// body) is read and dropped for this long before closing: closing with unread bytes would reset
// the connection, and the client could lose the response.
constexpr std::chrono::milliseconds kLinger{2000};

void address_of(int socket, bool peer, std::string& ip, int& port) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  const int result = peer ? ::getpeername(socket, reinterpret_cast<sockaddr*>(&address), &length)
                          : ::getsockname(socket, reinterpret_cast<sockaddr*>(&address), &length);
  if (result != 0) return;
  char text[INET6_ADDRSTRLEN] = {};
  if (address.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<const sockaddr_in*>(&address);
    ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
    port = ntohs(v4->sin_port);
  } else if (address.ss_family == AF_INET6) {
    const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&address);
    ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
    port = ntohs(v6->sin6_port);
  }
  ip = text;
}

// As much of `bytes` as the socket takes now; how much that was (0 when it would block or failed).
std::size_t send_some(int socket, const char* bytes, std::size_t size) {
  const ssize_t sent = ::send(socket, bytes, size, MSG_NOSIGNAL | MSG_DONTWAIT);
  return sent > 0 ? static_cast<std::size_t>(sent) : 0;
}

}  // namespace

struct ConnectionRoom::Connection {
  enum class State { reading, working, writing, lingering };
  int fd = -1;
  State state = State::reading;
  std::string input;             // received, not yet handed to a worker
  std::string output;            // the response being written
  std::size_t sent = 0;          // of output
  bool request_started = false;  // some bytes of the next request are in input
  bool continue_sent = false;    // the interim 100 of this request
  bool close_after_write = false;
  Clock::time_point since;       // when the current state began (which connection waited longest)
  Clock::time_point deadline;
  Exchange peer;                 // only the addresses: a template for this connection's exchanges

  std::size_t buffered() const { return input.size() + output.size() - sent; }
};

ConnectionRoom::ConnectionRoom(const HttpLimits& limits, std::function<void(Exchange&)> answer)
    : limits_(limits), answer_(std::move(answer)) {
  wake_fd_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) throw std::system_error(errno, std::generic_category(), "eventfd");
  for (std::size_t i = 0; i < limits_.workers; ++i) workers_.emplace_back([this] { work_loop(); });
  poller_ = std::thread([this] { poll_loop(); });
}

ConnectionRoom::~ConnectionRoom() {
  stop();
  join();
  ::close(wake_fd_);
}

void ConnectionRoom::wake() {
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t written = ::write(wake_fd_, &one, sizeof one);
}

void ConnectionRoom::admit(int socket) {
  {
    std::lock_guard lock(mutex_);
    if (!stopping_) {
      admitted_.push_back(socket);
      socket = -1;
    }
  }
  if (socket >= 0) {
    ::close(socket);
    return;
  }
  wake();
}

void ConnectionRoom::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_all();
  wake();
}

void ConnectionRoom::join() {
  if (poller_.joinable()) poller_.join();
  for (auto& worker : workers_)
    if (worker.joinable()) worker.join();
}

RoomCounters ConnectionRoom::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

// Workers answer complete requests until stop() and no request is left.
void ConnectionRoom::work_loop() {
  for (;;) {
    Finished item;
    {
      std::unique_lock lock(mutex_);
      work_ready_.wait(lock, [&] { return stopping_ || !to_answer_.empty(); });
      if (to_answer_.empty()) return;
      item = std::move(to_answer_.front());
      to_answer_.pop_front();
    }
    answer_(item.exchange);
    {
      std::lock_guard lock(mutex_);
      answered_.push_back(std::move(item));
    }
    wake();
  }
}

void ConnectionRoom::poll_loop() {
  std::map<std::uint64_t, std::unique_ptr<Connection>> connections;
  std::uint64_t next_id = 0;
  std::size_t buffered = 0;  // over every connection and every request with a worker
  bool stopping = false;
  Clock::time_point stop_deadline;

  const auto count = [&](std::uint64_t RoomCounters::*counter) {
    std::lock_guard lock(mutex_);
    ++(counters_.*counter);
  };
  const auto close_connection = [&](std::map<std::uint64_t, std::unique_ptr<Connection>>::iterator at) {
    buffered -= at->second->buffered();
    ::close(at->second->fd);
    return connections.erase(at);
  };
  const auto start_writing = [&](Connection& c, std::string response, bool close, Clock::time_point now) {
    buffered += response.size();
    c.output = std::move(response);
    c.sent = 0;
    c.close_after_write = close || stopping;
    c.state = Connection::State::writing;
    c.since = now;
    c.deadline = now + limits_.write_time;
  };
  // The room's own answer, after which the connection closes.
  const auto refuse = [&](Connection& c, int status, const std::string& message, Clock::time_point now) {
    buffered -= c.input.size();
    c.input.clear();
    start_writing(c, error_response(status, message, true), true, now);
    count(&RoomCounters::refused);
  };
  const auto start_waiting = [&](Connection& c, Clock::time_point now) {
    c.state = Connection::State::reading;
    c.since = now;
    c.request_started = !c.input.empty();
    c.continue_sent = false;
    c.deadline = now + (c.request_started ? limits_.request_time : limits_.idle);
  };
  // Looks at what a reading connection has received: hands a complete request to a worker, or
  // refuses it.
  const auto examine = [&](std::uint64_t id, Connection& c, Clock::time_point now) {
    if (c.input.empty()) return;
    if (!c.request_started) {
      c.request_started = true;
      c.deadline = now + limits_.request_time;
    }
    RequestFraming framing = frame_request(c.input, limits_);
    if (framing.state == RequestFraming::State::refused) return refuse(c, framing.status, framing.error, now);
    if (framing.state == RequestFraming::State::incomplete) {
      if (framing.head_bytes > 0 && framing.expects_continue && !c.continue_sent) {
        static constexpr char kContinue[] = "HTTP/1.1 100 Continue\r\n\r\n";
        send_some(c.fd, kContinue, sizeof kContinue - 1);
        c.continue_sent = true;
      }
      return;
    }
    Finished item{id, c.peer};
    item.exchange.request = take_request(c.input, framing);
    if (c.input.empty()) std::string().swap(c.input);
    c.state = Connection::State::working;
    c.since = now;
    {
      std::lock_guard lock(mutex_);
      to_answer_.push_back(std::move(item));
      ++counters_.requests;
    }
    work_ready_.notify_one();
  };

  std::vector<pollfd> polled;
  std::vector<std::uint64_t> polled_ids;
  for (;;) {
    std::vector<int> admitted;
    std::deque<Finished> answered;
    {
      std::lock_guard lock(mutex_);
      admitted.swap(admitted_);
      answered.swap(answered_);
      if (stopping_ && !stopping) {
        stopping = true;
        stop_deadline = Clock::now() + limits_.stop_time;
      }
    }
    Clock::time_point now = Clock::now();
    if (stopping) {
      // Nothing new is read: connections between requests close now, responses in flight are written.
      for (auto at = connections.begin(); at != connections.end();) {
        const Connection::State state = at->second->state;
        at = state == Connection::State::reading || state == Connection::State::lingering ? close_connection(at) : std::next(at);
      }
      if (connections.empty() || now >= stop_deadline) break;
    }

    for (int fd : admitted) {
      if (connections.size() >= limits_.max_connections) {
        // Room for the newcomer: the connection idle longest goes; with none idle, the newcomer.
        auto oldest = connections.end();
        for (auto at = connections.begin(); at != connections.end(); ++at) {
          const Connection& c = *at->second;
          if (c.state == Connection::State::reading && !c.request_started &&
              (oldest == connections.end() || c.since < oldest->second->since))
            oldest = at;
        }
        if (oldest == connections.end()) {
          const std::string busy =
              error_response(503, "too many connections (" + std::to_string(limits_.max_connections) + "): try again", true);
          send_some(fd, busy.data(), busy.size());
          ::close(fd);
          count(&RoomCounters::refused);
          continue;
        }
        close_connection(oldest);
        count(&RoomCounters::evicted);
      }
      ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
      const int on = 1;
      ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
      auto c = std::make_unique<Connection>();
      c->fd = fd;
      address_of(fd, true, c->peer.remote_ip, c->peer.remote_port);
      address_of(fd, false, c->peer.local_ip, c->peer.local_port);
      start_waiting(*c, now);
      connections.emplace(next_id++, std::move(c));
      std::lock_guard lock(mutex_);
      ++counters_.connections;
    }

    for (Finished& item : answered) {
      const auto at = connections.find(item.id);
      buffered -= item.exchange.request.size();
      if (at == connections.end()) continue;
      Connection& c = *at->second;
      start_writing(c, std::move(item.exchange.response), item.exchange.close, now);
      // Over the byte limit: the responses waiting longest to be taken go first.
      while (buffered > limits_.max_buffered_bytes) {
        auto slowest = connections.end();
        for (auto other = connections.begin(); other != connections.end(); ++other)
          if (other != at && other->second->state == Connection::State::writing &&
              (slowest == connections.end() || other->second->since < slowest->second->since))
            slowest = other;
        if (slowest == connections.end()) break;
        close_connection(slowest);
        count(&RoomCounters::evicted);
      }
    }

    // Deadlines: idle connections close, a request too slow to arrive gets 408, a response too
    // slow to be taken is abandoned.
    for (auto at = connections.begin(); at != connections.end();) {
      Connection& c = *at->second;
      if (c.state == Connection::State::working || now < c.deadline) {
        ++at;
        continue;
      }
      if (c.state != Connection::State::lingering) count(&RoomCounters::timed_out);
      if (c.state == Connection::State::reading && c.request_started) {
        refuse(c, 408, "request not received within " + std::to_string(limits_.request_time.count()) + " ms", now);
        ++at;
        continue;
      }
      at = close_connection(at);
    }
    {
      std::lock_guard lock(mutex_);
      counters_.open = connections.size();
    }

    polled.assign(1, pollfd{wake_fd_, POLLIN, 0});
    polled_ids.assign(1, 0);
    Clock::time_point wake_at = now + kLongestPoll;
    if (stopping) wake_at = std::min(wake_at, stop_deadline);
    const bool reading_allowed = buffered < limits_.max_buffered_bytes;
    for (const auto& [id, c] : connections) {
      if (c->state == Connection::State::working) continue;
      wake_at = std::min(wake_at, c->deadline);
      const short events = c->state == Connection::State::writing
                               ? POLLOUT
                               : (reading_allowed || c->state == Connection::State::lingering ? POLLIN : 0);
      polled.push_back({c->fd, events, 0});
      polled_ids.push_back(id);
    }
    const auto timeout = std::chrono::duration_cast<std::chrono::milliseconds>(wake_at - now).count() + 1;
    if (::poll(polled.data(), polled.size(), static_cast<int>(std::max<long long>(timeout, 0))) < 0 && errno != EINTR)
      break;
    if (polled[0].revents & POLLIN) {
      std::uint64_t ignored;
      [[maybe_unused]] const ssize_t read = ::read(wake_fd_, &ignored, sizeof ignored);
    }

    now = Clock::now();
    for (std::size_t i = 1; i < polled.size(); ++i) {
      if (polled[i].revents == 0) continue;
      const auto at = connections.find(polled_ids[i]);
      Connection& c = *at->second;
      bool keep = true;
      if (c.state == Connection::State::reading || c.state == Connection::State::lingering) {
        char chunk[kReadChunk];
        const ssize_t received = ::recv(c.fd, chunk, sizeof chunk, MSG_DONTWAIT);
        if (received > 0 && c.state == Connection::State::reading) {
          c.input.append(chunk, static_cast<std::size_t>(received));
          buffered += static_cast<std::size_t>(received);
          examine(at->first, c, now);
        } else if (received <= 0) {
          keep = received < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR);  // 0: the peer closed
        }
      } else if (c.state == Connection::State::writing) {
        if (polled[i].revents & (POLLERR | POLLHUP | POLLNVAL)) {
          keep = false;
        } else {
          const std::size_t sent = send_some(c.fd, c.output.data() + c.sent, c.output.size() - c.sent);
          c.sent += sent;
          buffered -= sent;
          if (c.sent == c.output.size()) {
            std::string().swap(c.output);  // a large response's memory goes back now, not at the next one
            c.sent = 0;
            if (stopping) {
              keep = false;
            } else if (c.close_after_write) {
              ::shutdown(c.fd, SHUT_WR);  // the response is complete; what the client still sends is dropped
              buffered -= c.input.size();
              c.input.clear();
              c.state = Connection::State::lingering;
              c.deadline = now + kLinger;
            } else {
              start_waiting(c, now);
              examine(at->first, c, now);  // a request sent behind the last one
            }
          }
        }
      }
      if (!keep) close_connection(at);
    }
  }
  for (auto at = connections.begin(); at != connections.end();) at = close_connection(at);
  {
    std::lock_guard lock(mutex_);
    counters_.open = 0;
    stopping_ = true;
    for (const int fd : admitted_) ::close(fd);
    admitted_.clear();
  }
  work_ready_.notify_all();
}

}  // namespace phongcl
