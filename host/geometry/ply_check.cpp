#include "geometry/ply_check.h"

#include <charconv>
#include <limits>
#include <map>
#include <optional>

#include "common/error.h"

namespace phongcl {
namespace {

struct ScalarType {
  unsigned bytes;
  bool is_signed;
  bool is_integer;
};

std::optional<ScalarType> scalar_type(std::string_view name) {
  static const std::map<std::string_view, ScalarType> kTypes = {
      {"char", {1, true, true}},    {"int8", {1, true, true}},     {"uchar", {1, false, true}},
      {"uint8", {1, false, true}},  {"short", {2, true, true}},    {"int16", {2, true, true}},
      {"ushort", {2, false, true}}, {"uint16", {2, false, true}},  {"int", {4, true, true}},
      {"int32", {4, true, true}},   {"uint", {4, false, true}},    {"uint32", {4, false, true}},
      {"float", {4, true, false}},  {"float32", {4, true, false}}, {"double", {8, true, false}},
      {"float64", {8, true, false}}};
  const auto found = kTypes.find(name);
  return found == kTypes.end() ? std::nullopt : std::optional(found->second);
}

struct Property {
  std::string name;
  ScalarType value;                      // a scalar's type, or a list's items'
  std::optional<ScalarType> list_count;  // set for a list
  bool corners = false;                  // a list of vertex indices: Assimp triangulates it
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;

  // The fewest bytes one record can take: a binary value's size, a list's count
  // alone; in ASCII a character and a separator per value.
  std::uint64_t least_record_bytes(bool binary) const {
    std::uint64_t bytes = 0;
    for (const Property& p : properties) bytes += binary ? (p.list_count ? p.list_count->bytes : p.value.bytes) : 2;
    return bytes;
  }
};

struct Header {
  PlyLayout layout;
  std::vector<Element> elements;
  bool big_endian = false;
};

// A word of the file as a message shows it: printable, and short.
std::string shown(std::string_view text) {
  constexpr std::size_t kShown = 40;
  std::string out = "'";
  for (char c : text.substr(0, kShown)) out += c >= 0x20 && c < 0x7f ? c : '?';
  return out + (text.size() > kShown ? "...'" : "'");
}

std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> words;
  for (std::size_t at = 0; at < line.size();) {
    const std::size_t start = line.find_first_not_of(" \t", at);
    if (start == std::string_view::npos) break;
    const std::size_t end = std::min(line.find_first_of(" \t", start), line.size());
    words.push_back(line.substr(start, end - start));
    at = end;
  }
  return words;
}

template <typename Number>
std::optional<Number> parse_whole(std::string_view word) {
  Number value{};
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size()) return std::nullopt;
  return value;
}

class HeaderReader {
 public:
  HeaderReader(std::string_view bytes, const std::filesystem::path& file) : bytes_(bytes), file_(file) {}

  Header read() {
    for (std::size_t at = 0;;) {
      const std::size_t end = bytes_.find('\n', at);
      if (end == std::string_view::npos || end >= kMaxPlyHeaderBytes) {
        if (end != std::string_view::npos || bytes_.size() >= kMaxPlyHeaderBytes)
          throw InputError(
              file_, "its header has no end_header in its first " + std::to_string(kMaxPlyHeaderBytes >> 20) + " MiB");
        throw InputError(file_, "its header ends before end_header (the file is cut short)");
      }
      std::string_view line = bytes_.substr(at, end - at);
      at = end + 1;
      header_.layout.crlf = line.ends_with('\r');
      if (header_.layout.crlf) line.remove_suffix(1);
      header_.layout.header_lines.emplace_back(line);
      if (read_line(line)) {
        header_.layout.data_offset = at;
        check_vertices();
        return std::move(header_);
      }
    }
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(file_, "header line " + std::to_string(header_.layout.header_lines.size()) + ": " + problem);
  }

  // True at end_header.
  bool read_line(std::string_view line) {
    // Printable text only: Assimp ends a word at a NUL or a form feed as well, so a name like
    // "vertex_indices\0x" would be one word here and "vertex_indices" there.
    for (char c : line)
      if ((c < 0x20 || c > 0x7e) && c != '\t')
        fail("holds a byte that is not printable text (" + std::to_string(static_cast<unsigned char>(c)) + ")");
    const std::vector<std::string_view> words = words_of(line);
    const std::size_t number = header_.layout.header_lines.size();
    if (number == 1) {
      if (line != "ply") fail("must be 'ply'");
      return false;
    }
    if (number == 2) {
      read_format(words);
      return false;
    }
    if (words.empty()) fail("is empty");
    const std::string_view keyword = words[0];
    if (keyword == "comment" || keyword == "obj_info") return false;
    if (keyword == "end_header" && words.size() == 1) return true;
    if (keyword == "element")
      read_element(words);
    else if (keyword == "property")
      read_property(words);
    else
      fail(shown(line) +
           " is not a PLY header line (element, property, "
           "comment or end_header)");
    return false;
  }

  void read_format(const std::vector<std::string_view>& words) {
    const bool known = words.size() == 3 && words[0] == "format" && words[2] == "1.0" &&
                       (words[1] == "ascii" || words[1] == "binary_little_endian" || words[1] == "binary_big_endian");
    if (!known)
      fail(
          "must be 'format ascii 1.0', 'format binary_little_endian 1.0' or "
          "'format binary_big_endian 1.0'");
    header_.layout.binary = words[1] != "ascii";
    header_.big_endian = words[1] == "binary_big_endian";
  }

  void read_element(const std::vector<std::string_view>& words) {
    if (words.size() != 3) fail("an element is 'element NAME COUNT'");
    const auto count = parse_whole<std::uint64_t>(words[2]);
    if (!count) fail("element " + shown(words[1]) + " has count " + shown(words[2]) + ", not a whole number >= 0");
    // Readers find an element by its name too: Assimp 5.2 frees memory it did not allocate on a
    // second "vertex" element.
    for (const Element& declared : header_.elements)
      if (declared.name == words[1]) fail("element " + shown(words[1]) + " is declared twice");
    header_.elements.push_back({std::string(words[1]), *count, {}});
  }

  ScalarType type_of(std::string_view name) const {
    if (auto type = scalar_type(name)) return *type;
    fail(shown(name) +
         " is not a PLY type (char, uchar, short, ushort, int, "
         "uint, float, double, or int8 to float64)");
  }

  void read_property(const std::vector<std::string_view>& words) {
    if (header_.elements.empty()) fail("a property before any element");
    Property property;
    if (words.size() == 5 && words[1] == "list") {
      property.list_count = type_of(words[2]);
      if (!property.list_count->is_integer) fail("a list's count must have an integer type, not " + shown(words[2]));
      property.value = type_of(words[3]);
      property.name = words[4];
      property.corners = property.name == "vertex_indices" || property.name == "vertex_index";
    } else if (words.size() == 3 && words[1] != "list") {
      property.value = type_of(words[1]);
      property.name = words[2];
    } else {
      fail(
          "a property is 'property TYPE NAME' or 'property list COUNT_TYPE "
          "TYPE NAME'");
    }
    // Readers find a property by its name: a second of one name (a vertex's z twice, its x missing)
    // is laid out by the header but read as neither.
    for (const Property& declared : header_.elements.back().properties)
      if (declared.name == property.name)
        fail("property " + shown(property.name) + " of element " + shown(header_.elements.back().name) +
             " is declared twice");
    header_.elements.back().properties.push_back(std::move(property));
  }

  void check_vertices() {
    for (const Element& element : header_.elements) {
      if (element.name != "vertex") continue;
      int axes = 0;
      for (const Property& p : element.properties)
        axes += !p.list_count && (p.name == "x" || p.name == "y" || p.name == "z");
      if (axes == 3) {
        header_.layout.vertices = element.count;
        return;
      }
    }
    throw InputError(file_, "its header declares no vertex element with x, y and z");
  }

  std::string_view bytes_;
  const std::filesystem::path& file_;
  Header header_;
};

// The data after the header, walked value by value as Assimp will read it.
class DataWalk {
 public:
  DataWalk(const Header& header, std::string_view data, const std::filesystem::path& file)
      : header_(header), data_(data), file_(file) {}

  std::uint64_t triangles() {
    check_sizes();
    for (const Element& element : header_.elements)
      for (std::uint64_t record = 0; record < element.count; ++record) {
        if (!header_.layout.binary) start_line(element, record);
        for (const Property& property : element.properties) walk(element, record, property);
        if (!header_.layout.binary) end_line(element, record);
      }
    return triangles_;
  }

 private:
  [[noreturn]] void fail(const Element& element, std::uint64_t record, const std::string& problem) const {
    throw InputError(
        file_, element.name + " " + std::to_string(record) + " of " + std::to_string(element.count) + ": " + problem);
  }

  // Every element's least size against the bytes there are, before a record is
  // read: a header claiming billions of faces in a small file fails at once.
  void check_sizes() const {
    const bool binary = header_.layout.binary;
    long double least = 0;
    for (const Element& element : header_.elements) {
      const std::uint64_t record = element.least_record_bytes(binary);
      if (record == 0 && element.count > 0)
        throw InputError(file_, "element " + shown(element.name) + " declares " + std::to_string(element.count) +
                                    " records of no properties");
      least += static_cast<long double>(element.count) * record;
    }
    // An ASCII file's last value needs no separator after it.
    const long double available = static_cast<long double>(data_.size()) + (binary ? 0 : 1);
    if (least > available) {
      const bool representable = least < static_cast<long double>(std::numeric_limits<std::uint64_t>::max());
      throw InputError(file_, "its header declares elements that need at least " +
                                  (representable ? std::to_string(static_cast<std::uint64_t>(least)) : "2^64") +
                                  " bytes, but only " + std::to_string(data_.size()) + " follow it");
    }
  }

  void walk(const Element& element, std::uint64_t record, const Property& property) {
    if (!property.list_count) return value(element, record, property.value);
    const std::uint64_t count = list_count(element, record, *property.list_count);
    if (property.corners && count == 0) fail(element, record, "a list of " + property.name + " with no corners");
    const std::uint64_t least_item = header_.layout.binary ? property.value.bytes : 2;
    if (count > (data_.size() - at_ + (header_.layout.binary ? 0 : 1)) / least_item)
      fail(element, record,
           "a list of " + std::to_string(count) + " " + property.name + " runs past the end of the file");
    if (property.corners && count >= 3) triangles_ += count - 2;
    for (std::uint64_t item = 0; item < count; ++item) value(element, record, property.value);
  }

  std::uint64_t list_count(const Element& element, std::uint64_t record, ScalarType type) {
    if (!header_.layout.binary) {
      const std::string_view word = token(element, record);
      const auto count = parse_whole<std::uint64_t>(word);
      if (!count) fail(element, record, "a list's count " + shown(word) + " is not a whole number >= 0");
      return *count;
    }
    const std::string_view bytes = take(element, record, type.bytes);
    std::uint64_t bits = 0;
    for (unsigned i = 0; i < type.bytes; ++i) {
      const unsigned at = header_.big_endian ? i : type.bytes - 1 - i;
      bits = bits << 8 | static_cast<unsigned char>(bytes[at]);
    }
    if (type.is_signed && bits >> (8 * type.bytes - 1)) fail(element, record, "a list with a negative count");
    return bits;
  }

  void value(const Element& element, std::uint64_t record, ScalarType type) {
    if (header_.layout.binary) {
      take(element, record, type.bytes);
      return;
    }
    std::string_view word = token(element, record);
    if (word.starts_with('+')) word.remove_prefix(1);
    const bool number =
        type.is_integer ? parse_whole<std::int64_t>(word).has_value() : parse_whole<double>(word).has_value();
    if (!number) fail(element, record, shown(word) + " is not " + (type.is_integer ? "an integer" : "a number"));
  }

  std::string_view take(const Element& element, std::uint64_t record, std::size_t bytes) {
    if (data_.size() - at_ < bytes) fail(element, record, "the file ends inside it (cut short)");
    const std::string_view taken = data_.substr(at_, bytes);
    at_ += bytes;
    return taken;
  }

  // Assimp reads an ASCII record from a line of its own: values of the next record on the same
  // line, or a record spread over lines, misalign every value after them (it aborted, or allocated
  // gigabytes, on such files). Empty lines between records are passed over.
  void start_line(const Element& element, std::uint64_t record) {
    at_ = std::min(data_.find_first_not_of(" \t\r\n", at_), data_.size());
    if (at_ == data_.size()) fail(element, record, "the file ends before it (cut short)");
  }

  void end_line(const Element& element, std::uint64_t record) {
    at_ = std::min(data_.find_first_not_of(" \t\r", at_), data_.size());
    if (at_ < data_.size() && data_[at_] != '\n')
      fail(element, record, "its line holds more values than its element declares (a record is one line)");
  }

  // An ASCII value, on the record's line. Assimp reads a number's digits into 64 bits and, past 19
  // of them, neither stops nor moves on: every value after it is read from the wrong place.
  std::string_view token(const Element& element, std::uint64_t record) {
    constexpr std::size_t kMaxDigitsInARow = 18;
    const std::size_t start = std::min(data_.find_first_not_of(" \t\r", at_), data_.size());
    if (start == data_.size() || data_[start] == '\n')
      fail(element, record, "its line ends before its values do (a record is one line)");
    at_ = std::min(data_.find_first_of(" \t\r\n", start), data_.size());
    const std::string_view word = data_.substr(start, at_ - start);
    std::size_t digits = 0;
    for (char c : word)
      if ((digits = c >= '0' && c <= '9' ? digits + 1 : 0) > kMaxDigitsInARow)
        fail(element, record, shown(word) + " has more than " + std::to_string(kMaxDigitsInARow) + " digits in a row");
    return word;
  }

  const Header& header_;
  std::string_view data_;
  const std::filesystem::path& file_;
  std::size_t at_ = 0;
  std::uint64_t triangles_ = 0;
};

}  // namespace

PlyLayout check_ply(std::string_view bytes, const std::filesystem::path& file) {
  Header header = HeaderReader(bytes, file).read();
  header.layout.triangles = DataWalk(header, bytes.substr(header.layout.data_offset), file).triangles();
  return std::move(header.layout);
}

}  // namespace phongcl
