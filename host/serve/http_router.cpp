#include "serve/http_router.h"

#include <array>
#include <exception>
#include <string_view>

namespace phongcl {

namespace {

bool is_http_method(std::string_view method) {
  constexpr std::array<std::string_view, 9> kMethods = {"GET",     "HEAD",    "POST",  "PUT",  "DELETE",
                                                        "CONNECT", "OPTIONS", "TRACE", "PATCH"};
  for (std::string_view known : kMethods)
    if (method == known) return true;
  return false;
}

}  // namespace

void HttpRouter::add(std::string method, std::string path, Handler handler) {
  handlers_[{std::move(method), std::move(path)}] = std::move(handler);
}

HttpResponse HttpRouter::answer(const HttpRequest& request) const {
  if (!is_http_method(request.method)) return error_response(400, "malformed HTTP request: unknown method");
  const auto found = handlers_.find({request.method == "HEAD" ? "GET" : request.method, request.path});
  if (found == handlers_.end()) return error_response(404, "not found: " + request.method + " " + request.path);
  HttpResponse response;
  try {
    found->second(request, response);
  } catch (const std::exception& error) {
    return error_response(500, std::string("internal error: ") + error.what());
  } catch (...) {
    return error_response(500, "internal error");
  }
  return response;
}

}  // namespace phongcl
