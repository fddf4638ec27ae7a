#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "common/utf8.h"

namespace phongcl {
namespace {

std::string child_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

// nlohmann's messages start with "[json.exception.parse_error.101] "; the rest (with line and
// column for syntax errors) is what the user needs.
std::string json_problem(const nlohmann::json::exception& error) {
  const std::string what = error.what();
  const std::size_t end_of_tag = what.find("] ");
  return "invalid JSON: " + (end_of_tag == std::string::npos ? what : what.substr(end_of_tag + 2));
}

// Deeper documents are refused while parsing: the object reader recurses into transform children
// and every value carries its path, so an unbounded depth would exhaust the stack (and memory).
// 256 levels allow 127 nested transforms (each is an object inside a "children" array).
constexpr int kMaxJsonDepth = 256;

}  // namespace

nlohmann::json parse_json(std::string_view json_text, const std::filesystem::path& source) {
  // Before nlohmann sees it: its message would quote the bad bytes, which no JSON message can carry.
  if (const auto bad = first_invalid_utf8(json_text)) {
    char byte[8];
    std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(json_text[*bad]));
    throw InputError(source, "invalid JSON: not UTF-8 (byte " + std::string(byte) + " at offset " + std::to_string(*bad) + ")");
  }
  const auto limit_depth = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxJsonDepth)
      throw InputError(source, "invalid JSON: nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    return true;
  };
  try {
    return nlohmann::json::parse(json_text, limit_depth);
  } catch (const nlohmann::json::exception& error) {
    throw InputError(source, json_problem(error));
  }
}

std::string format_number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

JsonValue::JsonValue(const nlohmann::json& json, std::string path, const std::filesystem::path& file)
    : json_(&json), path_(std::move(path)), file_(&file) {}

std::string JsonValue::place() const { return path_.empty() ? "the top level" : path_; }

void JsonValue::fail(const std::string& problem) const {
  throw InputError(*file_, place() + " " + problem);
}

double JsonValue::number() const {
  if (!json_->is_number()) fail("must be a number");
  const double value = json_->get<double>();
  // JSON has no NaN or infinity, but a huge literal still would not survive the float G-buffer.
  if (!std::isfinite(value) || std::abs(value) > std::numeric_limits<float>::max())
    fail("must be a finite single-precision number (got " + format_number(value) + ")");
  return value;
}

int JsonValue::integer() const {
  if (!json_->is_number()) fail("must be an integer");
  const double value = json_->get<double>();
  if (value != std::floor(value) || value < std::numeric_limits<int>::min() ||
      value > std::numeric_limits<int>::max())
    fail("must be an integer (got " + format_number(value) + ")");
  return static_cast<int>(value);
}

std::string JsonValue::string() const {
  if (!json_->is_string()) fail("must be a string");
  return json_->get<std::string>();
}

bool JsonValue::boolean() const {
  if (!json_->is_boolean()) fail("must be true or false");
  return json_->get<bool>();
}

std::vector<double> JsonValue::numbers(std::size_t count) const {
  if (!json_->is_array() || json_->size() != count)
    fail("must be an array of " + std::to_string(count) + " numbers");
  std::vector<double> values;
  values.reserve(count);
  for (const JsonValue& element : elements()) values.push_back(element.number());
  return values;
}

glm::dvec3 JsonValue::vec3() const {
  const std::vector<double> xyz = numbers(3);
  return {xyz[0], xyz[1], xyz[2]};
}

std::vector<JsonValue> JsonValue::elements() const {
  if (!json_->is_array()) fail("must be an array");
  std::vector<JsonValue> result;
  result.reserve(json_->size());
  for (std::size_t i = 0; i < json_->size(); ++i)
    result.emplace_back((*json_)[i], path_ + "[" + std::to_string(i) + "]", *file_);
  return result;
}

JsonObject JsonValue::object() const { return JsonObject(*this); }

JsonObject::JsonObject(const JsonValue& value) : value_(value) {
  if (!value.json().is_object()) value.fail("must be an object");
}

void JsonObject::expect_keys(std::initializer_list<std::string_view> allowed) const {
  for (const auto& item : value_.json().items()) {
    if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
    std::string expected;
    for (std::string_view name : allowed) expected += (expected.empty() ? "" : ", ") + std::string(name);
    fail("unknown key '" + item.key() + "' in " + value_.place() + " (expected: " + expected + ")");
  }
}

bool JsonObject::has(std::string_view key) const { return value_.json().contains(key); }

JsonValue JsonObject::at(std::string_view key) const {
  std::optional<JsonValue> found = find(key);
  if (!found) fail("missing key '" + std::string(key) + "' in " + value_.place());
  return *found;
}

std::optional<JsonValue> JsonObject::find(std::string_view key) const {
  const auto found = value_.json().find(key);
  if (found == value_.json().end()) return std::nullopt;
  return JsonValue(*found, child_path(value_.path(), key), value_.file());
}

void JsonObject::fail(const std::string& problem) const { throw InputError(value_.file(), problem); }

}  // namespace phongcl
