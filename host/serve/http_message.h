#pragma once
// A request and its response as the routes see them: plain strings, whatever library reads and
// writes the connection (serve/http_server.h).
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace phongcl {

struct HttpRequest {
  std::string method;  // as sent: GET, HEAD, PUT, ...
  std::string path;    // URL-decoded, without the query
  std::vector<std::pair<std::string, std::string>> params;  // the query, URL-decoded, in order
  std::string body;
};

struct HttpResponse {
  int status = 200;
  std::string content_type;
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;  // besides Content-Type and Content-Length

  void set_header(std::string name, std::string value) { headers.emplace_back(std::move(name), std::move(value)); }
  void set_content(std::string content, std::string type) {
    body = std::move(content);
    content_type = std::move(type);
  }
};

// The request of `method` for `target` (path and query as sent, percent-encoded; '+' in the query
// is a space) with `body`.
HttpRequest make_request(std::string method, std::string_view target, std::string body);

// {"error": message} and a line break; bytes that are not UTF-8 are replaced, never echoed raw.
std::string error_json(const std::string& message);
// A response with that body.
HttpResponse error_response(int status, const std::string& message);

}  // namespace phongcl
