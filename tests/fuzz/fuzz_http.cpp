// libFuzzer harness: one HTTP request, as bytes off the wire, through the server's own path:
// Beast's parser held to the server's limits and the refusals before any handler
// (serve/request_framing.h), then, for a whole request, the routes (RelightServer::answer), with a
// real Relighter on PoCL behind them. A finding is a crash, a sanitizer report, an exception leaving
// a handler (a 500: the router turns every one into that), or a response that is not a well-formed
// HTTP response with a JSON error body for every error status. A 503 (no frame in time, while a
// new kernel compiles) is an answer, not a finding.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "color/color_config.h"
#include "serve/relight_server.h"

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
        live(session, kScene, "fuzz.json", phongcl::RenderSettings{}, phongcl::ColorConfig::builtin()),
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

std::string_view current_input;  // the input being answered, written out with a finding

// libFuzzer writes no crash file here (the LLVM inside PoCL takes SIGABRT's handler over), so a
// finding writes its input itself, where 30-fuzz.sh collects the fuzzers' crash files.
void write_input(const char* name) {
  if (std::FILE* file = std::fopen(name, "wb")) {
    std::fwrite(current_input.data(), 1, current_input.size(), file);
    std::fclose(file);
  }
}

// The input as a C string literal would spell it, for a log that outlives the fuzzer's files.
std::string escaped(std::string_view bytes) {
  std::string text;
  for (const char c : bytes.substr(0, 2000)) {
    if (c == '\\' || c == '"') text += {'\\', c};
    else if (c == '\r') text += "\\r";
    else if (c == '\n') text += "\\n";
    else if (c >= ' ' && c <= '~') text += c;
    else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned char>(c));
      text += hex;
    }
  }
  return text;
}

[[noreturn]] void finding(const std::string& what, const std::string& response) {
  write_input("crash-fuzz_http-finding");
  std::fprintf(stderr,
               "fuzz_http: %s\n--- input (also in crash-fuzz_http-finding) ---\n\"%s\"\n"
               "--- response ---\n%.2000s\n--- end ---\n",
               what.c_str(), escaped(current_input).c_str(), response.c_str());
  std::abort();
}

// One response: status line, headers, then (but to HEAD) errors carry {"error": "..."}.
void check_response(const std::string& response, bool head = false) {
  if (response.rfind("HTTP/1.1 ", 0) != 0 || response.size() < 12) finding("no status line", response);
  const int status = std::atoi(response.c_str() + 9);
  if (status < 100 || status > 599 || status == 500) finding("status " + std::to_string(status), response);
  const std::size_t head_end = response.find("\r\n\r\n");
  if (head_end == std::string::npos) finding("no end of head", response);
  if (status >= 400 && !head) {
    const nlohmann::json document = nlohmann::json::parse(response.substr(head_end + 4), nullptr, false);
    if (document.is_discarded() || !document.contains("error") || !document["error"].is_string())
      finding("an error without a JSON {\"error\": ...} body", response);
  }
}

Server* server = nullptr;  // never destroyed: PoCL's own threads outlive main's statics

}  // namespace

// The server and its first kernel before the first input: a build takes seconds, not a finding.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  server = new Server;
  server->server.answer("GET /api/image?format=png HTTP/1.1\r\n\r\n");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  current_input = input;
  const std::optional<std::string> response = server->server.answer(input);
  if (!response) return 0;  // not a whole request: a connection waits for the rest, then 408
  // A request line begins with its method: only "HEAD " gets a response without its body.
  check_response(*response, input.starts_with("HEAD "));
  return 0;
}
