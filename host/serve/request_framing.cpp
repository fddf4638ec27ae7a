#include "serve/request_framing.h"

#include <sstream>

#include <boost/beast/core/string.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/write.hpp>

namespace phongcl {

namespace http = boost::beast::http;

void hold_to_limits(RequestParser& parser, const HttpLimits& limits) {
  parser.header_limit(static_cast<std::uint32_t>(limits.max_head_bytes));
  parser.body_limit(limits.max_body_bytes);
}

std::optional<HttpResponse> refusal_for(boost::beast::error_code error, const HttpLimits& limits) {
  if (error.category() != http::make_error_code(http::error::need_more).category() ||
      error == http::error::end_of_stream || error == http::error::partial_message)
    return std::nullopt;
  if (error == http::error::header_limit)
    return error_response(431, "request head over " + std::to_string(limits.max_head_bytes >> 10) + " KiB");
  if (error == http::error::body_limit)
    return error_response(413,
                          "request too large (the limit is " + std::to_string(limits.max_body_bytes >> 20) + " MiB)");
  if (error == http::error::bad_content_length) return error_response(400, "malformed Content-Length");
  if (error == http::error::bad_transfer_encoding)
    return error_response(411, "send the body with a Content-Length (Transfer-Encoding is not read)");
  return error_response(400, "malformed HTTP request (" + error.message() + ")");
}

std::optional<HttpResponse> refusal_for_head(const RequestParser& parser) {
  const auto& request = parser.get();
  if (request.count(http::field::transfer_encoding) > 0)
    return error_response(411, "send the body with a Content-Length (Transfer-Encoding is not read)");
  if (request.target().size() > kMaxTargetBytes)
    return error_response(414, "request target over " + std::to_string(kMaxTargetBytes >> 10) + " KiB");
  // curl -d and HTML forms send form encoding; a JSON scene sent so would be read as parameters.
  const std::string_view type = request[http::field::content_type];
  const auto starts = [&](std::string_view prefix) {
    return type.size() >= prefix.size() && boost::beast::iequals(type.substr(0, prefix.size()), prefix);
  };
  if ((starts("application/x-www-form-urlencoded") || starts("multipart/form-data")) &&
      parser.content_length().value_or(0) > 0)
    return error_response(415, "the body must be JSON sent with Content-Type: application/json (got " +
                                   std::string(type) +
                                   "; with curl: -H 'Content-Type: application/json' --data-binary @scene.json)");
  return std::nullopt;
}

bool expects_continue(const RequestParser& parser) {
  return boost::beast::iequals(parser.get()[http::field::expect], "100-continue");
}

HttpRequest request_of(RequestParser& parser) {
  auto request = parser.release();
  return make_request(std::string(request.method_string()), request.target(), std::move(request.body()));
}

WireResponse wire_response(HttpResponse response, bool head, bool keep_alive) {
  WireResponse wire;
  wire.result(static_cast<unsigned>(response.status));
  if (!response.content_type.empty()) wire.set(http::field::content_type, response.content_type);
  for (const auto& [name, value] : response.headers) wire.insert(name, value);
  if (response.status == 503 && wire.count(http::field::retry_after) == 0) wire.set(http::field::retry_after, "1");
  if (response.status != 204 && response.status >= 200) wire.content_length(response.body.size());
  if (!head) wire.body() = std::move(response.body);
  wire.keep_alive(keep_alive);
  return wire;
}

std::optional<std::string> answer_bytes(std::string_view bytes, const HttpLimits& limits, const Answer& answer) {
  RequestParser parser;
  hold_to_limits(parser, limits);
  parser.eager(true);
  boost::beast::error_code error;
  std::size_t used = 0;
  std::optional<HttpResponse> refusal;
  while (!error && !parser.is_done() && used < bytes.size()) {
    used += parser.put(boost::asio::buffer(bytes.data() + used, bytes.size() - used), error);
    if (!error && parser.is_header_done() && (refusal = refusal_for_head(parser))) break;
  }
  if (error && error != http::error::need_more) refusal = refusal_for(error, limits);
  if (!refusal && !parser.is_done()) return std::nullopt;
  const bool head = !refusal && parser.get().method() == http::verb::head;
  const bool keep_alive = !refusal && parser.get().keep_alive();
  std::ostringstream text;
  text << wire_response(refusal ? std::move(*refusal) : answer(request_of(parser)), head, keep_alive);
  return text.str();
}

}  // namespace phongcl
