#pragma once
// What handlers throw to answer an error; the routes turn each into its status with {"error": ...}.
#include <stdexcept>

namespace phongcl {

// 400: the request is malformed (a parameter, the body).
class BadRequest : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// 500: the request was fine but the server could not carry it out (e.g. a write failed).
class ServerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// 503: the server cannot take this request now (too many waiting); the client should retry.
class Unavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace phongcl
