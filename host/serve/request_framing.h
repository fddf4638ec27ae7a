#pragma once
// What the connection reads and writes, apart from the socket: Boost.Beast's parser held to
// HttpLimits, the refusals a request gets before any handler sees it, and a response as Beast
// writes it. serve/http_server.h reads sockets with it; answer_bytes() is the same path for bytes
// in memory (the HTTP fuzzer's way in).
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include <boost/beast/core/error.hpp>
#include <boost/beast/http/message.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/string_body.hpp>

#include "serve/http_limits.h"
#include "serve/http_message.h"

namespace phongcl {

using RequestParser = boost::beast::http::request_parser<boost::beast::http::string_body>;
using WireResponse = boost::beast::http::response<boost::beast::http::string_body>;
using Answer = std::function<HttpResponse(const HttpRequest&)>;

// Request targets longer than this are refused (414): the API's longest is a few hundred bytes.
inline constexpr std::size_t kMaxTargetBytes = 8u << 10;

// Sets the parser's head and body limits.
void hold_to_limits(RequestParser& parser, const HttpLimits& limits);

// The refusal for what the parser reported: 431 (head too large), 413 (body too large), 411
// (Transfer-Encoding), 400 (anything else malformed); none when the error is the connection's
// (closed, reset, cancelled), not the request's.
std::optional<HttpResponse> refusal_for(boost::beast::error_code error, const HttpLimits& limits);

// Once the head is in, what no endpoint reads: a chunked body (411), a form-encoded one (415:
// every endpoint reads JSON), a target over kMaxTargetBytes (414).
std::optional<HttpResponse> refusal_for_head(const RequestParser& parser);

// "Expect: 100-continue" (exactly, in any case): the client waits for an interim 100 before the body.
bool expects_continue(const RequestParser& parser);

// The parsed request, for the routes.
HttpRequest request_of(RequestParser& parser);

// `response` as the connection sends it: to HEAD without its body; "Connection: close" unless
// `keep_alive`; "Retry-After: 1" on every 503.
WireResponse wire_response(HttpResponse response, bool head, bool keep_alive);

// One request's bytes to its response's, as a connection reading them would send it (refusals
// included); nothing while the bytes are not a whole request yet.
std::optional<std::string> answer_bytes(std::string_view bytes, const HttpLimits& limits, const Answer& answer);

}  // namespace phongcl
