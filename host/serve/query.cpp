#include "serve/query.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "scene/json_reader.h"  // format_number

namespace phongcl {

Query::Query(const HttpRequest& request, const std::vector<std::string_view>& allowed) : request_(request) {
  for (const auto& param : request.params) {
    const std::string& name = param.first;
    bool known = false;
    for (std::string_view a : allowed) known = known || a == name;
    if (!known) {
      std::string expected;
      for (std::string_view a : allowed) expected += (expected.empty() ? "" : ", ") + std::string(a);
      throw BadRequest("unknown parameter '" + name + "'" +
                       (expected.empty() ? " (this endpoint takes none)" : " (expected " + expected + ")"));
    }
    const auto named = [&](const auto& other) { return other.first == name; };
    if (std::count_if(request.params.begin(), request.params.end(), named) > 1)
      throw BadRequest("parameter '" + name + "' given more than once");
  }
}

std::optional<std::string> Query::text(const std::string& name) const {
  for (const auto& [given, value] : request_.params)
    if (given == name) return value;
  return std::nullopt;
}

long long Query::integer(const std::string& name, long long min, long long max, long long fallback) const {
  const auto value = text(name);
  if (!value) return fallback;
  long long result = 0;
  const auto [end, error] = std::from_chars(value->data(), value->data() + value->size(), result);
  if (error != std::errc() || end != value->data() + value->size())
    throw BadRequest("parameter '" + name + "' must be an integer (got '" + *value + "')");
  if (result < min || result > max)
    throw BadRequest("parameter '" + name + "' must be in [" + std::to_string(min) + ", " + std::to_string(max) + "] (got " + *value + ")");
  return result;
}

double Query::number(const std::string& name, double min, double max, double fallback) const {
  const auto value = text(name);
  if (!value) return fallback;
  char* end = nullptr;
  const double result = std::strtod(value->c_str(), &end);
  if (value->empty() || end != value->c_str() + value->size() || !std::isfinite(result))
    throw BadRequest("parameter '" + name + "' must be a finite number (got '" + *value + "')");
  if (result < min || result > max)
    throw BadRequest("parameter '" + name + "' must be in [" + format_number(min) + ", " + format_number(max) +
                     "] (got " + *value + ")");
  return result;
}

}  // namespace phongcl
