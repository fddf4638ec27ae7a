#include "serve/request_framing.h"

#include <algorithm>
#include <cctype>
#include <charconv>

#include <nlohmann/json.hpp>

namespace phongcl {

namespace {

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
  return text;
}

bool starts_with_ignoring_case(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() && equal_ignoring_case(text.substr(0, prefix.size()), prefix);
}

RequestFraming refused(int status, std::string error) {
  RequestFraming framing;
  framing.state = RequestFraming::State::refused;
  framing.status = status;
  framing.error = std::move(error);
  return framing;
}

const char* reason_phrase(int status) {
  switch (status) {
    case 400: return "Bad Request";
    case 408: return "Request Timeout";
    case 411: return "Length Required";
    case 413: return "Payload Too Large";
    case 415: return "Unsupported Media Type";
    case 431: return "Request Header Fields Too Large";
    case 503: return "Service Unavailable";
  }
  return "Error";
}

}  // namespace

RequestFraming frame_request(std::string_view input, const HttpLimits& limits) {
  // The head ends at the first empty line (CRLF, or a bare LF, which the library then refuses).
  const std::size_t crlf = input.find("\r\n\r\n"), lf = input.find("\n\n");
  const std::size_t end = std::min(crlf == std::string_view::npos ? crlf : crlf + 4, lf == std::string_view::npos ? lf : lf + 2);
  if (end == std::string_view::npos || end > limits.max_head_bytes) {
    if (input.size() > limits.max_head_bytes || end != std::string_view::npos)
      return refused(431, "request head over " + std::to_string(limits.max_head_bytes >> 10) + " KiB");
    return {};
  }
  RequestFraming framing;
  framing.head_bytes = end;
  const std::string_view head = input.substr(0, end);
  bool has_length = false, form_body = false;
  std::string type;
  // Header lines after the request line.
  for (std::size_t begin = head.find('\n') + 1; begin < head.size();) {
    std::size_t line_end = head.find('\n', begin);
    if (line_end == std::string_view::npos) line_end = head.size();
    const std::string_view line = head.substr(begin, line_end - begin);
    const std::size_t colon = line.find(':');
    if (colon != std::string_view::npos) {
      const std::string_view name = line.substr(0, colon), value = trimmed(line.substr(colon + 1));
      if (equal_ignoring_case(name, "Content-Length")) {
        std::size_t length = 0;
        const auto [at, error] = std::from_chars(value.data(), value.data() + value.size(), length);
        if (error != std::errc() || at != value.data() + value.size() || (has_length && length != framing.body_bytes))
          return refused(400, "malformed Content-Length");
        framing.body_bytes = length;
        has_length = true;
      } else if (equal_ignoring_case(name, "Transfer-Encoding")) {
        return refused(411, "send the body with a Content-Length (Transfer-Encoding is not read)");
      } else if (equal_ignoring_case(name, "Content-Type")) {
        form_body = starts_with_ignoring_case(value, "application/x-www-form-urlencoded") ||
                    starts_with_ignoring_case(value, "multipart/form-data");
        type = value;
      } else if (equal_ignoring_case(name, "Expect")) {
        // The room answers 100-continue itself. The library would answer any value that URL-decodes
        // to it ("100%2Dcontinue") with a stray interim response, so it sees no Expect at all.
        framing.expects_continue = framing.expects_continue || equal_ignoring_case(value, "100-continue");
        framing.unread_lines.push_back({begin, line_end + 1});
      } else if (equal_ignoring_case(name, "Range") || equal_ignoring_case(name, "If-Range")) {
        framing.unread_lines.push_back({begin, line_end + 1});
      }
    }
    begin = line_end + 1;
  }
  if (framing.body_bytes > limits.max_body_bytes)
    return refused(413, "request too large (the limit is " + std::to_string(limits.max_body_bytes >> 20) + " MiB)");
  // curl -d and HTML forms send form encoding, which the library would split into parameters.
  if (form_body && framing.body_bytes > 0)
    return refused(415, "the body must be JSON sent with Content-Type: application/json (got " + type +
                            "; with curl: -H 'Content-Type: application/json' --data-binary @scene.json)");
  framing.state = input.size() >= framing.total() ? RequestFraming::State::complete : RequestFraming::State::incomplete;
  return framing;
}

std::string take_request(std::string& input, const RequestFraming& framing) {
  std::string request = input.substr(0, framing.total());
  input.erase(0, framing.total());
  // Last line first, so that each erase leaves the earlier lines' offsets as they were.
  for (auto line = framing.unread_lines.rbegin(); line != framing.unread_lines.rend(); ++line)
    request.erase(line->begin, line->end - line->begin);
  return request;
}

std::string error_response(int status, const std::string& message, bool close) {
  const std::string body =
      nlohmann::json{{"error", message}}.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  return "HTTP/1.1 " + std::to_string(status) + " " + reason_phrase(status) +
         "\r\nContent-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
         (close ? "\r\nConnection: close" : "") + (status == 503 ? "\r\nRetry-After: 1" : "") + "\r\n\r\n" + body;
}

}  // namespace phongcl
