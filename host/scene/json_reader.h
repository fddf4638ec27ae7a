#pragma once
// Strict, typed reading of scene JSON. Every value knows its path in the file ("lights[1].color"),
// so each problem becomes a one-line InputError naming the file, the place and what was expected.
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace phongcl {

class JsonObject;

// A JSON document, or a one-line InputError naming `source`: text that is not UTF-8 (the first
// bad byte and its offset), a syntax error (line and column), nesting deeper than 256 levels.
nlohmann::json parse_json(std::string_view json_text, const std::filesystem::path& source);

// "1e+39", "-0.5": numbers as messages quote them.
std::string format_number(double value);

// One JSON value and its place in the file. Holds references: the document and the file path
// must outlive it.
class JsonValue {
 public:
  JsonValue(const nlohmann::json& json, std::string path, const std::filesystem::path& file);

  const nlohmann::json& json() const { return *json_; }
  const std::string& path() const { return path_; }
  const std::filesystem::path& file() const { return *file_; }
  // "lights[1]", or "the top level" for the document itself.
  std::string place() const;
  // Throws InputError(file, "<place> <problem>").
  [[noreturn]] void fail(const std::string& problem) const;

  // Numbers must be finite and within float range: the G-buffer and the kernel are single precision.
  double number() const;
  int integer() const;  // a whole number that fits an int (640 and 640.0 both accepted)
  std::string string() const;
  bool boolean() const;  // true or false, nothing else (no 0/1, no "true")
  std::vector<double> numbers(std::size_t count) const;  // an array of exactly `count` numbers
  glm::dvec3 vec3() const;
  std::vector<JsonValue> elements() const;               // an array, each element with its path
  JsonObject object() const;

 private:
  const nlohmann::json* json_;
  std::string path_;
  const std::filesystem::path* file_;
};

// A JSON object whose keys can be checked against the ones a section allows.
class JsonObject {
 public:
  explicit JsonObject(const JsonValue& value);  // throws unless the value is an object

  // Throws "unknown key 'k' in <place> (expected: a, b, c)" for the first key not in `allowed`.
  void expect_keys(std::initializer_list<std::string_view> allowed) const;
  bool has(std::string_view key) const;
  JsonValue at(std::string_view key) const;  // throws "missing key 'k' in <place>"
  std::optional<JsonValue> find(std::string_view key) const;
  const JsonValue& value() const { return value_; }

 private:
  // Throws InputError(file, problem): for problems about the object itself, not one of its values.
  [[noreturn]] void fail(const std::string& problem) const;

  JsonValue value_;
};

}  // namespace phongcl
