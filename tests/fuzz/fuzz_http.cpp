// libFuzzer harness: one HTTP request, as bytes off the wire, through the server's own path: the
// connection room's framing (serve/request_framing.h), then, for a whole request, httplib's parser
// and the routes (RelightServer::answer, what a worker runs), with a real Relighter on PoCL behind
// them. A finding is a crash, a sanitizer report, an exception leaving a handler or the library (a
// 500: answer() and the routes turn every one into that), or a response that is not a well-formed
// HTTP response with a JSON error body for every error status. A 503 (no frame in time, while a
// new kernel compiles) is an answer, not a finding.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "serve/relight_server.h"
#include "serve/request_framing.h"

namespace {

// An 8x6 G-buffer, two materials, so requests reach a real frame within milliseconds.
phongcl::GBuffer small_gbuffer() {
  phongcl::GBuffer g;
  g.width = 8;
  g.height = 6;
  g.data_window = g.display_window = {0, 0, 7, 5};
  const std::size_t pixels = g.pixel_count();
  for (auto* planes : {&g.position, &g.normal})
    for (auto& plane : *planes) plane.assign(pixels, 0.0f);
  g.material.assign(pixels, 0.0f);
  for (std::size_t i = 0; i < pixels; ++i) {
    g.position[0][i] = static_cast<float>(i % 8) - 4.0f;
    g.position[1][i] = static_cast<float>(i / 8) - 3.0f;
    g.normal[2][i] = 1.0f;
    g.material[i] = i % 5 == 0 ? -1.0f : static_cast<float>(i % 2);
  }
  return g;
}

constexpr const char* kScene = R"({"camera": {"eye": [0, 0, 10], "look_at": [0, 0, 0], "width": 8, "height": 6},
  "lights": [{"type": "point", "position": [1, 2, 5], "color": [1, 1, 1]}],
  "materials": [{"kd": [0.5, 0.5, 0.5]}, {"kd": [0.2, 0.3, 0.9], "ks": [1, 1, 1], "shininess": 20}]})";

struct Server {
  Server()
      : session(small_gbuffer(), ""),
        live(session, kScene, "fuzz.json", phongcl::RenderSettings{}),
        server(live, options()) {}
  static phongcl::ServeOptions options() {
    phongcl::ServeOptions options;
    options.device = "fuzz";
    // Waits bounded well under libFuzzer's -timeout: a long poll for a frame that never comes.
    options.frame_timeout = std::chrono::milliseconds(5'000);
    options.max_poll = std::chrono::milliseconds(20);
    options.limits.workers = 1;
    return options;
  }
  phongcl::RelightSession session;
  phongcl::LiveRelighter live;
  phongcl::RelightServer server;
};

[[noreturn]] void finding(const std::string& what, const std::string& response) {
  std::fprintf(stderr, "fuzz_http: %s\n--- response ---\n%.2000s\n", what.c_str(), response.c_str());
  std::abort();
}

// One response: status line, headers, then (but to HEAD) errors carry {"error": "..."}.
void check_response(const std::string& response, bool head = false) {
  if (response.rfind("HTTP/1.1 ", 0) != 0 || response.size() < 12) finding("no status line", response);
  const int status = std::atoi(response.c_str() + 9);
  if (status < 100 || status > 599 || status == 500) finding("status " + std::to_string(status), response);
  const std::size_t head_end = response.find("\r\n\r\n");
  if (head_end == std::string::npos) finding("no end of head", response);
  const std::string body = response.substr(head_end + 4);
  if (status >= 400 && !head) {
    const nlohmann::json document = nlohmann::json::parse(body, nullptr, false);
    if (document.is_discarded() || !document.contains("error") || !document["error"].is_string())
      finding("an error without a JSON {\"error\": ...} body", response);
  }
}

Server* server = nullptr;  // never destroyed: PoCL's own threads outlive main's statics

phongcl::Exchange answered(std::string request) {
  phongcl::Exchange exchange;
  exchange.request = std::move(request);
  exchange.remote_ip = exchange.local_ip = "127.0.0.1";
  server->server.answer(exchange);
  return exchange;
}

}  // namespace

// The server and its first kernel before the first input: a build takes seconds, not a finding.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  server = new Server;
  answered("GET /api/image?format=png HTTP/1.1\r\n\r\n");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const phongcl::RequestFraming framing = phongcl::frame_request(input, phongcl::HttpLimits{});
  if (framing.state == phongcl::RequestFraming::State::refused) {
    check_response(phongcl::error_response(framing.status, framing.error, true));
    return 0;
  }
  if (framing.state != phongcl::RequestFraming::State::complete) return 0;  // the room waits, then 408
  std::string bytes(input);
  check_response(answered(phongcl::take_request(bytes, framing)).response, input.rfind("HEAD ", 0) == 0);
  return 0;
}
