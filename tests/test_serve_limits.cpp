// phongcl serve against clients that do not play along: bytes that are not UTF-8, bodies that are
// not JSON, clients that send slowly, stay idle or hold long polls, and a stop while they do. The
// server is the real one on a loopback port; the clients are raw sockets, byte for byte.
// (scripts/checks/55-serve-clients.sh runs the same against the `phongcl serve` binary and prints
// the figures: answer times while slow clients are connected, time to stop on SIGTERM, RSS.)
#include <gtest/gtest.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "cl/device.h"
#include "cli_runner.h"
#include "opencl_required.h"
#include "serve_support.h"
#include "temp_dir.h"
#include "wait_until.h"

namespace phongcl {
namespace {

using nlohmann::json;
using testing::RunningServer;
using testing::wait_until;
using namespace std::chrono_literals;

// Longer than any answer here takes on a loaded machine: reaching it means the server hung.
constexpr auto kHung = 60s;

// A TCP connection to the server that sends exactly the bytes it is given.
class RawClient {
 public:
  explicit RawClient(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  }
  ~RawClient() { ::close(fd_); }
  RawClient(const RawClient&) = delete;
  RawClient& operator=(const RawClient&) = delete;

  bool connected() const { return connected_; }
  bool send(const std::string& bytes) { return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size()); }
  // Everything the server sends until it closes the connection or `timeout` passes.
  std::string read_until_closed(std::chrono::milliseconds timeout = kHung) {
    std::string received;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      pollfd polled{fd_, POLLIN, 0};
      if (left.count() <= 0 || ::poll(&polled, 1, static_cast<int>(left.count())) <= 0) return received;
      char chunk[65536];
      const ssize_t got = ::recv(fd_, chunk, sizeof chunk, 0);
      if (got <= 0) {
        closed_ = true;
        return received;
      }
      received.append(chunk, static_cast<std::size_t>(got));
    }
  }
  // One response (head and Content-Length body), leaving the connection open.
  std::string read_response(std::chrono::milliseconds timeout = kHung) {
    std::string received;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      const std::size_t head_end = received.find("\r\n\r\n");
      if (head_end != std::string::npos) {
        const std::size_t length_at = received.find("Content-Length: ");
        const std::size_t length = length_at < head_end ? std::stoul(received.substr(length_at + 16)) : 0;
        if (received.size() >= head_end + 4 + length) return received;
      }
      pollfd polled{fd_, POLLIN, 0};
      if (::poll(&polled, 1, 100) <= 0) continue;
      char chunk[65536];
      const ssize_t got = ::recv(fd_, chunk, sizeof chunk, 0);
      if (got <= 0) {
        closed_ = true;
        break;
      }
      received.append(chunk, static_cast<std::size_t>(got));
    }
    return received;
  }
  bool closed() const { return closed_; }

 private:
  int fd_;
  bool connected_ = false;
  bool closed_ = false;
};

// A client that sends a request's head a header line every 50 ms and never ends it, until destroyed.
class SlowSender {
 public:
  explicit SlowSender(int port)
      : thread_([this, port] {
          RawClient client(port);
          client.send("GET /api/stats HTTP/1.1\r\n");
          while (!done_) {
            client.send("X-Slow: 1\r\n");
            std::this_thread::sleep_for(50ms);
          }
        }) {}
  ~SlowSender() {
    done_ = true;
    thread_.join();
  }
  SlowSender(const SlowSender&) = delete;
  SlowSender& operator=(const SlowSender&) = delete;

 private:
  std::atomic<bool> done_ = false;  // before thread_, which reads it from its first moment
  std::thread thread_;
};

int status_of(const std::string& response) { return response.rfind("HTTP/1.1 ", 0) == 0 ? std::stoi(response.substr(9, 3)) : 0; }

json body_of(const std::string& response) {
  const std::size_t head_end = response.find("\r\n\r\n");
  return head_end == std::string::npos ? json() : json::parse(response.substr(head_end + 4), nullptr, false);
}

std::string error_of(const std::string& response) {
  const json body = body_of(response);
  return body.is_object() && body.contains("error") && body["error"].is_string() ? body["error"].get<std::string>() : "";
}

// One raw request on a fresh connection, and its response.
std::string round_trip(int port, const std::string& request) {
  RawClient client(port);
  EXPECT_TRUE(client.connected());
  client.send(request);
  return client.read_response();
}

class ServeHostile : public ::testing::Test {
 protected:
  void SetUp() override {
    PHONGCL_REQUIRE_OPENCL(!list_devices().empty());
    server_ = std::make_unique<RunningServer>();
  }
  std::unique_ptr<RunningServer> server_;
};

// `curl 'http://127.0.0.1:PORT/%ff'` ended the process (exit 134): the 404 message quoted the raw
// path into JSON, and nlohmann threw on the byte outside any handler.
TEST_F(ServeHostile, PathsThatAreNotUtf8AreJson404s) {
  for (const std::string path : {"/%ff", "/\xff\xfe", "/api/%c0%af", "/api/scene%ed%a0%80"}) {
    SCOPED_TRACE(path);
    const std::string response = round_trip(server_->port(), "GET " + path + " HTTP/1.1\r\nHost: x\r\n\r\n");
    EXPECT_EQ(status_of(response), 404) << response;
    EXPECT_NE(error_of(response).find("not found: GET /"), std::string::npos) << response;
  }
  auto client = server_->client();
  const auto stats = client.Get("/api/stats");
  ASSERT_TRUE(stats) << "the server should still be answering";
  EXPECT_EQ(stats->status, 200);
}

TEST_F(ServeHostile, QueryNamesAndValuesThatAreNotUtf8AreJson400s) {
  for (const std::string query : {"/api/image?%ff=1", "/api/image?format=%ff%fe", "/api/frame?after=%c3"}) {
    SCOPED_TRACE(query);
    const std::string response = round_trip(server_->port(), "GET " + query + " HTTP/1.1\r\nHost: x\r\n\r\n");
    EXPECT_EQ(status_of(response), 400) << response;
    EXPECT_FALSE(error_of(response).empty()) << response;
  }
}

// A PUT whose body is not UTF-8 got a 500 with nlohmann's message (the bytes quoted in it).
TEST_F(ServeHostile, BodiesThatAreNotUtf8Are400sNamingTheOffset) {
  auto client = server_->client();
  const auto scene = client.Put("/api/scene", "{\"lights\": \"\xff\"}", "application/json");
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->status, 400) << scene->body;
  EXPECT_NE(error_of("HTTP/1.1 400\r\n\r\n" + scene->body).find("not UTF-8 (byte 0xFF at offset 12)"), std::string::npos)
      << scene->body;
  const auto settings = client.Put("/api/settings", "{\"precision\": \"\xc3\x28\"}", "application/json");
  ASSERT_TRUE(settings);
  EXPECT_EQ(settings->status, 400) << settings->body;
  EXPECT_NE(settings->body.find("not UTF-8 (byte 0xC3 at offset 15)"), std::string::npos) << settings->body;
}

// `curl -d @scene.json` sends a form: the scene came back as "unknown parameter '{...}'".
TEST_F(ServeHostile, FormEncodedBodiesAre415sSayingWhatToSend) {
  auto client = server_->client();
  const auto put = client.Put("/api/scene", testing::read_text(testing::kServeSceneFile), "application/x-www-form-urlencoded");
  ASSERT_TRUE(put);
  EXPECT_EQ(put->status, 415) << put->body;
  EXPECT_NE(put->body.find("Content-Type: application/json"), std::string::npos) << put->body;
}

// The room's own refusals, before any worker: chunked bodies, oversized heads and bodies, a
// malformed length, all as JSON errors.
TEST_F(ServeHostile, FramingErrorsAreJsonAndCloseTheConnection) {
  struct Case {
    std::string request;
    int status;
    const char* says;
  };
  const Case cases[] = {
      {"PUT /api/scene HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n5\r\nhello\r\n0\r\n\r\n", 411, "Content-Length"},
      {"PUT /api/scene HTTP/1.1\r\nContent-Length: 99999999999\r\n\r\n", 413, "request too large"},
      {"PUT /api/scene HTTP/1.1\r\nContent-Length: 12x\r\n\r\n", 400, "malformed Content-Length"},
      {"GET / HTTP/1.1\r\nX: " + std::string(70'000, 'a') + "\r\n\r\n", 431, "request head over 64 KiB"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.says);
    RawClient client(server_->port());
    client.send(c.request);
    const std::string response = client.read_until_closed();
    EXPECT_EQ(status_of(response), c.status) << response;
    EXPECT_NE(error_of(response).find(c.says), std::string::npos) << response;
    EXPECT_TRUE(client.closed());
  }
}

// curl sends "Expect: 100-continue" before a large body and waits for the interim answer.
TEST_F(ServeHostile, ExpectContinueGetsOneInterimAnswer) {
  const std::string scene = testing::read_text(testing::kServeSceneFile);
  RawClient client(server_->port());
  client.send("PUT /api/scene HTTP/1.1\r\nContent-Type: application/json\r\nExpect: 100-continue\r\nContent-Length: " +
              std::to_string(scene.size()) + "\r\n\r\n");
  EXPECT_EQ(client.read_response(), "HTTP/1.1 100 Continue\r\n\r\n");
  client.send(scene);
  const std::string response = client.read_response();
  EXPECT_EQ(status_of(response), 200) << response;
}

// The library URL-decodes header values: "100%2Dcontinue" drew a 100 Continue ahead of the answer
// to a request that had nothing more to send.
TEST_F(ServeHostile, OtherExpectationsGetNoInterimAnswer) {
  for (const std::string expectation : {"100%2Dcontinue", "100-continue-please", "x"}) {
    SCOPED_TRACE(expectation);
    const std::string response =
        round_trip(server_->port(), "GET /nowhere HTTP/1.1\r\nExpect: " + expectation + "\r\n\r\n");
    EXPECT_EQ(status_of(response), 404) << response;
    EXPECT_EQ(response.find("100 Continue"), std::string::npos) << response;
    EXPECT_NE(error_of(response).find("not found: GET /nowhere"), std::string::npos) << response;
  }
}

// The fuzzer's finding: the library cut an error's JSON body to a Range header's bytes ("{\"er"
// for bytes=0-3), and a page's too. Every response is whole, whatever range is asked for.
TEST_F(ServeHostile, RangeHeadersGetWholeResponses) {
  for (const std::string range : {"bytes=0-3", "bytes=2-", "bytes=-1", "bytes=0-0,5-9", "bytes=9-1", "lines=1"}) {
    SCOPED_TRACE(range);
    const std::string missing = round_trip(server_->port(), "GET /nowhere HTTP/1.1\r\nRange: " + range + "\r\n\r\n");
    EXPECT_EQ(status_of(missing), 404) << missing;
    EXPECT_NE(error_of(missing).find("not found: GET /nowhere"), std::string::npos) << missing;
    const std::string bad = round_trip(server_->port(), "GET /api/image?format=gif HTTP/1.1\r\nIf-Range: x\r\nRange: " +
                                                            range + "\r\n\r\n");
    EXPECT_EQ(status_of(bad), 400) << bad;
    EXPECT_FALSE(error_of(bad).empty()) << bad;
    const std::string page = round_trip(server_->port(), "GET / HTTP/1.1\r\nRange: " + range + "\r\n\r\n");
    EXPECT_EQ(status_of(page), 200) << page.substr(0, 200);
    EXPECT_NE(page.find("</html>"), std::string::npos) << page.substr(0, 200);
  }
}

// Short limits, so that deadlines pass within the test.
HttpLimits quick_limits() {
  HttpLimits limits;
  limits.request_time = 300ms;
  limits.idle = 300ms;
  limits.max_waiting = 2;
  limits.max_connections = 8;
  return limits;
}

class ServeLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    PHONGCL_REQUIRE_OPENCL(!list_devices().empty());
  }
};

TEST_F(ServeLimits, RequestsTooSlowGet408AndIdleConnectionsClose) {
  RunningServer server({}, quick_limits());
  RawClient slow(server.port());
  slow.send("GET /api/stats HTTP/1.1\r\nHost: x\r\n");  // and never the blank line
  const std::string response = slow.read_until_closed();
  EXPECT_EQ(status_of(response), 408) << response;
  EXPECT_TRUE(slow.closed());
  RawClient idle(server.port());
  EXPECT_EQ(idle.read_until_closed(), "");
  EXPECT_TRUE(idle.closed()) << "an idle connection is closed after HttpLimits::idle";
  EXPECT_GE(server.server().counters().timed_out, 2u);
}

// Past max_connections a newcomer is served and the connection idle longest is closed for it.
TEST_F(ServeLimits, TheConnectionIdleLongestMakesRoom) {
  HttpLimits limits = quick_limits();
  limits.idle = 60s;
  RunningServer server({}, limits);
  std::vector<std::unique_ptr<RawClient>> idle;
  for (std::size_t i = 0; i < limits.max_connections; ++i) idle.push_back(std::make_unique<RawClient>(server.port()));
  ASSERT_TRUE(wait_until([&] { return server.server().counters().open >= limits.max_connections; }, kHung))
      << "the idle connections were never all open";
  EXPECT_EQ(status_of(round_trip(server.port(), "GET /api/stats HTTP/1.1\r\nHost: x\r\n\r\n")), 200);
  EXPECT_EQ(idle.front()->read_until_closed(), "");
  EXPECT_TRUE(idle.front()->closed()) << "the first idle connection made room";
  EXPECT_GE(server.server().counters().evicted, 1u);
}

// 32 connections sending a header line at a time, 200 idle sockets and every long poll the
// server allows took all of its 32 threads: /api/stats waited until they let go. Now they hold
// sockets, and the API answers while they are all still connected (and still sending).
TEST_F(ServeLimits, SlowIdleAndWaitingClientsLeaveTheApiAnswering) {
  HttpLimits limits;  // the defaults `phongcl serve` runs with
  limits.request_time = 600s;  // the slow senders stay for the whole test
  limits.idle = 600s;
  RunningServer server({}, limits);
  const int port = server.port();
  std::vector<std::unique_ptr<RawClient>> idle;
  for (int i = 0; i < 200; ++i) idle.push_back(std::make_unique<RawClient>(port));
  std::vector<std::unique_ptr<SlowSender>> slow;
  for (int i = 0; i < 32; ++i) slow.push_back(std::make_unique<SlowSender>(port));
  ASSERT_TRUE(wait_until([&] { return server.server().counters().open >= 200 + 32; }, kHung))
      << "the idle and slow connections were never all open";
  auto client = server.client();
  const std::string version = client.Get("/api/image?format=jpeg")->get_header_value("X-Frame-Version");
  std::vector<std::unique_ptr<RawClient>> polls;
  for (std::size_t i = 0; i < limits.max_waiting; ++i) {
    polls.push_back(std::make_unique<RawClient>(port));
    polls.back()->send("GET /api/frame?timeout_ms=60000&after=" + version + " HTTP/1.1\r\nHost: x\r\n\r\n");
  }
  // A request is counted when a worker takes it and holds a waiting place a moment later: wait
  // for the places, or the request beyond them may take one.
  const auto waiting = [&] { return body_of("HTTP/1.1 200\r\n\r\n" + client.Get("/api/stats")->body)["waiting_for_frames"].get<std::size_t>(); };
  ASSERT_TRUE(wait_until([&] { return waiting() >= limits.max_waiting; }, kHung))
      << "fewer than " << limits.max_waiting << " requests ever waited";

  const std::string beyond = round_trip(port, "GET /api/frame?timeout_ms=60000&after=" + version + " HTTP/1.1\r\n\r\n");
  EXPECT_EQ(status_of(beyond), 503) << beyond;
  EXPECT_NE(error_of(beyond).find("too many requests waiting for frames (8)"), std::string::npos) << beyond;
  EXPECT_NE(beyond.find("Retry-After: 1"), std::string::npos) << beyond;

  client.set_read_timeout(kHung);
  const auto stats = client.Get("/api/stats");
  ASSERT_TRUE(stats) << "/api/stats did not answer while slow clients were connected";
  EXPECT_EQ(stats->status, 200);
  EXPECT_EQ(status_of(round_trip(port, "GET / HTTP/1.1\r\nHost: x\r\n\r\n")), 200) << "the page";
  EXPECT_GE(server.server().counters().open, 200u + 32u + limits.max_waiting) << "every slow client still connected";
}

// SIGTERM waited for a slow client without limit (23 s in the probe). A stop now ends the server
// within HttpLimits::stop_time whatever its clients do: one sending a header a time, one not
// reading a large response, one in a long poll.
TEST_F(ServeLimits, StopEndsTheServerWhateverClientsDo) {
  HttpLimits limits = quick_limits();
  limits.request_time = limits.idle = 600s;
  auto server = std::make_unique<RunningServer>(std::filesystem::path(), limits);
  const int port = server->port();
  std::optional<SlowSender> slow(std::in_place, port);
  RawClient not_reading(port);
  for (int i = 0; i < 8; ++i) not_reading.send("GET /api/image?format=exr HTTP/1.1\r\nHost: x\r\n\r\n");
  RawClient poll(port);
  poll.send("GET /api/frame?timeout_ms=60000&after=999999 HTTP/1.1\r\nHost: x\r\n\r\n");
  ASSERT_TRUE(wait_until([&] { return server->server().counters().requests >= 2; }, kHung))
      << "the server never took the requests";

  auto stopped = std::async(std::launch::async, [&] { server.reset(); });
  const bool in_time = stopped.wait_for(kHung) == std::future_status::ready;
  slow.reset();  // lets a server that waits for its slow client end, so a failure is reported, not hung
  EXPECT_TRUE(in_time) << "the server did not stop while a slow client was connected";
}

// --save is checked when the server starts; a write that fails later is a 500 with the reason.
TEST_F(ServeLimits, SaveFailuresSayWhy) {
  testing::TempDir dir("serve_save_fail");
  std::filesystem::create_directories(dir / "gone");
  RunningServer server(dir / "gone" / "scene.json");
  std::filesystem::remove_all(dir / "gone");
  auto client = server.client();
  const auto saved = client.Post("/api/save", "", "application/json");
  ASSERT_TRUE(saved);
  EXPECT_EQ(saved->status, 500) << saved->body;
  EXPECT_NE(saved->body.find("save failed: "), std::string::npos) << saved->body;
  EXPECT_NE(saved->body.find("gone/scene.json"), std::string::npos) << saved->body;
  EXPECT_NE(saved->body.find("No such file or directory"), std::string::npos) << saved->body;
}

TEST(ServeCliSave, BadSavePathsAreRefusedAtStart) {
  testing::TempDir dir("serve_save_start");
  struct Case {
    std::string save;
    const char* says;
  };
  const Case cases[] = {
      {dir.path.string(), "it is a directory"},
      {(dir / "missing" / "scene.json").string(), "does not exist"},
      {"scenes/default/gbuffer.exr", "an output cannot replace an input"},
      {"scenes/default/scene.json", "--save 'scenes/default/scene.json' and --scene"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.save);
    const testing::CliRun run = testing::run_phongcl("serve --scene scenes/default/scene.json --port 0 --save " + c.save);
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find(c.says), std::string::npos) << run.err;
    EXPECT_EQ(run.out.find("url "), std::string::npos) << "it must not start: " << run.out;
  }
}

}  // namespace
}  // namespace phongcl
