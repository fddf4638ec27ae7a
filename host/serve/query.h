#pragma once
// Reading a request's query string strictly: unknown parameters, malformed numbers and values out
// of range are errors (BadRequest, which the server answers with 400 and the message).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "serve/http_errors.h"
#include "serve/http_message.h"

namespace phongcl {

class Query {
 public:
  // Throws BadRequest naming the first parameter not in `allowed`, or one given twice.
  Query(const HttpRequest& request, const std::vector<std::string_view>& allowed);
  std::optional<std::string> text(const std::string& name) const;
  long long integer(const std::string& name, long long min, long long max, long long fallback) const;
  double number(const std::string& name, double min, double max, double fallback) const;

 private:
  const HttpRequest& request_;
};

}  // namespace phongcl
