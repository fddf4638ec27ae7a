#pragma once
// Requests to their handlers by method and exact path. HEAD is answered by the GET handler (the
// connection leaves the body out); a path with no handler is a 404, a method HTTP does not define a
// 400, and whatever a handler throws a 500: every answer carries a body, errors {"error": ...}.
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "serve/http_message.h"

namespace phongcl {

class HttpRouter {
 public:
  using Handler = std::function<void(const HttpRequest&, HttpResponse&)>;
  void add(std::string method, std::string path, Handler handler);
  HttpResponse answer(const HttpRequest& request) const;

 private:
  std::map<std::pair<std::string, std::string>, Handler> handlers_;  // by method and path
};

}  // namespace phongcl
