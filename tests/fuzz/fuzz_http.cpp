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
#include <optional>
#include <string>
#include <string_view>

#include <brotli/decode.h>
#include <nlohmann/json.hpp>
#include <zlib.h>

#include "color/color_config.h"
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

// Whether the library reads the request as HEAD (no body in its answer): the request line's first
// word, which cpp-httplib finds by splitting at spaces and trimming spaces and tabs from each piece.
bool is_head_request(std::string_view request) {
  std::string_view line = request.substr(0, request.find("\r\n"));
  const auto blank = [](char c) { return c == ' ' || c == '\t'; };
  for (std::size_t begin = 0; begin < line.size();) {
    std::size_t end = line.find(' ', begin);
    if (end == std::string_view::npos) end = line.size();
    std::string_view word = line.substr(begin, end - begin);
    while (!word.empty() && blank(word.front())) word.remove_prefix(1);
    while (!word.empty() && blank(word.back())) word.remove_suffix(1);
    if (!word.empty()) return word == "HEAD";
    begin = end + 1;
  }
  return false;
}

// The response's Content-Encoding, spelt as the library writes it, empty where there is none.
std::string content_encoding(std::string_view head) {
  const std::string_view field = "\r\nContent-Encoding: ";
  const std::size_t at = head.find(field);
  if (at == std::string_view::npos) return "";
  const std::size_t begin = at + field.size();
  return std::string(head.substr(begin, head.find("\r\n", begin) - begin));
}

std::optional<std::string> gunzip(std::string_view bytes) {
  z_stream stream{};
  if (inflateInit2(&stream, 15 + 16) != Z_OK) return std::nullopt;  // 16: a gzip wrapper
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = static_cast<uInt>(bytes.size());
  std::string text;
  int result = Z_OK;
  while (result == Z_OK) {
    char chunk[16384];
    stream.next_out = reinterpret_cast<Bytef*>(chunk);
    stream.avail_out = sizeof chunk;
    result = inflate(&stream, Z_NO_FLUSH);
    text.append(chunk, sizeof chunk - stream.avail_out);
  }
  inflateEnd(&stream);
  return result == Z_STREAM_END ? std::optional(text) : std::nullopt;
}

std::optional<std::string> unbrotli(std::string_view bytes) {
  BrotliDecoderState* state = BrotliDecoderCreateInstance(nullptr, nullptr, nullptr);
  const auto* next_in = reinterpret_cast<const std::uint8_t*>(bytes.data());
  std::size_t available_in = bytes.size();
  std::string text;
  BrotliDecoderResult result = BROTLI_DECODER_RESULT_NEEDS_MORE_OUTPUT;
  while (result == BROTLI_DECODER_RESULT_NEEDS_MORE_OUTPUT) {
    std::uint8_t chunk[16384];
    std::uint8_t* next_out = chunk;
    std::size_t available_out = sizeof chunk;
    result = BrotliDecoderDecompressStream(state, &available_in, &next_in, &available_out, &next_out, nullptr);
    text.append(reinterpret_cast<const char*>(chunk), sizeof chunk - available_out);
  }
  BrotliDecoderDestroyInstance(state);
  return result == BROTLI_DECODER_RESULT_SUCCESS ? std::optional(text) : std::nullopt;
}

// The body as the routes wrote it: the library compresses JSON for a client that accepts gzip or br.
std::optional<std::string> decoded_body(std::string_view body, const std::string& encoding) {
  if (encoding.empty()) return std::string(body);
  if (encoding == "gzip") return gunzip(body);
  if (encoding == "br") return unbrotli(body);
  return std::nullopt;
}

// One response: status line, headers, then (but to HEAD) errors carry {"error": "..."}.
void check_response(const std::string& response, bool head = false) {
  if (response.rfind("HTTP/1.1 ", 0) != 0 || response.size() < 12) finding("no status line", response);
  const int status = std::atoi(response.c_str() + 9);
  if (status < 100 || status > 599 || status == 500) finding("status " + std::to_string(status), response);
  const std::size_t head_end = response.find("\r\n\r\n");
  if (head_end == std::string::npos) finding("no end of head", response);
  if (status >= 400 && !head) {
    const std::string_view whole = response;
    const std::optional<std::string> body =
        decoded_body(whole.substr(head_end + 4), content_encoding(whole.substr(0, head_end)));
    if (!body) finding("an error body that does not decode as its Content-Encoding says", response);
    const nlohmann::json document = nlohmann::json::parse(*body, nullptr, false);
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
  current_input = input;
  const phongcl::RequestFraming framing = phongcl::frame_request(input, phongcl::HttpLimits{});
  if (framing.state == phongcl::RequestFraming::State::refused) {
    check_response(phongcl::error_response(framing.status, framing.error, true));
    return 0;
  }
  if (framing.state != phongcl::RequestFraming::State::complete) return 0;  // the room waits, then 408
  std::string bytes(input);
  check_response(answered(phongcl::take_request(bytes, framing)).response, is_head_request(input));
  return 0;
}
