// PLY validation before assimp (ply_check.h). The header rules and the body walk follow
// the PLY spec; where assimp 5.2.5 reads a well-formed file differently (elements it does
// not know, see below) the file is refused rather than modelled.
#include "proxima/scene/ply_check.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/file_extension.h"
#include "proxima/core/limits.h"

namespace proxima {
namespace fs = std::filesystem;

namespace {

struct ScalarType {
  int bytes;
  bool integer;
  int64_t min, max;  // integer range
};
const std::map<std::string, ScalarType>& ply_types() {
  static const std::map<std::string, ScalarType> types = {
      {"char", {1, true, -128, 127}},
      {"int8", {1, true, -128, 127}},
      {"uchar", {1, true, 0, 255}},
      {"uint8", {1, true, 0, 255}},
      {"short", {2, true, -32768, 32767}},
      {"int16", {2, true, -32768, 32767}},
      {"ushort", {2, true, 0, 65535}},
      {"uint16", {2, true, 0, 65535}},
      {"int", {4, true, INT32_MIN, INT32_MAX}},
      {"int32", {4, true, INT32_MIN, INT32_MAX}},
      {"uint", {4, true, 0, UINT32_MAX}},
      {"uint32", {4, true, 0, UINT32_MAX}},
      {"float", {4, false, 0, 0}},
      {"float32", {4, false, 0, 0}},
      {"double", {8, false, 0, 0}},
      {"float64", {8, false, 0, 0}}};
  return types;
}

struct Property {
  std::string name;
  bool list = false;
  ScalarType count;  // lists only
  ScalarType value;
};
struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

// The elements assimp's PLY parser reads instance by instance. Any other name it parses
// as a count of 0 (strtoul10 of the name itself) and skips no lines, so the lines of such
// an element would feed the elements after it.
bool assimp_reads(const std::string& element) {
  return element == "vertex" || element == "face" || element == "tristrips" || element == "edge" ||
         element == "material";
}

// The list assimp takes a face's vertex indices from.
bool is_index_list(const Element& e, const Property& p) {
  return (e.name == "face" || e.name == "tristrips") && (p.name == "vertex_index" || p.name == "vertex_indices");
}

struct Header {
  bool ascii = false;
  bool big_endian = false;
  size_t body_offset = 0;
  std::vector<Element> elements;
};

Header parse_header(const fs::path& path, const std::string& head) {
  auto fail = [&](const std::string& why) -> void { fail_input(path.string() + ": PLY header " + why); };
  // A `.ply` must start with the magic line (assimp loops forever reading a file that
  // begins with an empty line and a garbled format).
  if (head.size() > 3 && head[3] != '\n' && head[3] != '\r') fail("does not start with the line 'ply'");
  Header h;
  bool format = false;
  std::set<std::string> names;
  size_t pos = 0;
  for (int number = 1;; ++number) {
    const size_t eol = head.find('\n', pos);
    if (eol == std::string::npos) fail("has no end_header in its first 64 KiB");
    std::string line = head.substr(pos, eol - pos);
    const bool crlf = !line.empty() && line.back() == '\r';
    if (crlf) line.pop_back();
    // assimp 5.2 loops forever on NUL bytes in a header line.
    for (char c : line)
      if (!(c == '\t' || (c >= ' ' && c <= '~'))) fail("line " + std::to_string(number) + " is not ASCII text");
    pos = eol + 1;
    if (number == 1) continue;  // the magic, checked by the caller (assimp accepts it in any case)
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    // Keywords are matched exactly, as assimp's parser does: it misses `end_headeR`, reads
    // the binary body as header and crashes (SEGV).
    const std::string keyword = line.substr(0, line.find_first_of(" \t"));
    if (keyword == "end_header") {
      if (!format) fail("has no valid format line (ascii, binary_little_endian or binary_big_endian 1.0)");
      // assimp's line reader stops at the CR and starts a binary body on the LF.
      if (crlf && !h.ascii) fail("of a binary file ends in CR LF");
      h.body_offset = pos;
      return h;
    } else if (keyword == "format") {
      if (w.size() != 3 || !(w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian") ||
          w[2] != "1.0")
        fail("has an unknown format line '" + line.substr(0, 40) + "'");
      format = true;
      h.ascii = w[1] == "ascii";
      h.big_endian = w[1] == "binary_big_endian";
    } else if (keyword == "property") {
      // `property TYPE NAME` or `property list TYPE TYPE NAME`: assimp takes `property float(y`
      // and crashes in post-processing (BUS).
      const auto& types = ply_types();
      const bool scalar = w.size() == 3 && types.count(w[1]);
      const bool list = w.size() == 5 && w[1] == "list" && types.count(w[2]) && types.count(w[3]);
      if (!scalar && !list) fail("has a malformed property line '" + line.substr(0, 40) + "'");
      if (h.elements.empty()) fail("has a property line before any element line");
      Element& e = h.elements.back();
      Property p;
      p.name = w.back();
      p.list = list;
      p.value = types.at(list ? w[3] : w[1]);
      if (list) p.count = types.at(w[2]);
      if (list && !p.count.integer) fail("has a list count that is not an integer type in '" + line.substr(0, 40) + "'");
      if (is_index_list(e, p) && !(list && p.value.integer))
        fail("declares '" + p.name + "' of '" + e.name + "' as something else than a list of integers");
      e.properties.push_back(p);
    } else if (keyword == "element") {
      uint64_t n = 0;
      const std::string count = w.size() > 2 ? w[2] : "";
      const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), n);
      if (w.size() != 3 || ec != std::errc() || end != count.data() + count.size())
        fail("has a malformed element line '" + line.substr(0, 40) + "'");
      // assimp reads counts as 32-bit, and the leading digits of a name it does not know
      // as that element's count.
      if (n > UINT32_MAX) fail("declares " + count + " '" + w[1] + "' elements, more than 2^32 - 1");
      if (std::isdigit(static_cast<unsigned char>(w[1][0]))) fail("has an element name starting with a digit '" + w[1] + "'");
      if (!names.insert(w[1]).second) fail("declares the element '" + w[1] + "' twice");
      h.elements.push_back({w[1], n, {}});
    } else if (keyword != "comment" && keyword != "obj_info") {
      fail("has an unknown line '" + line.substr(0, 40) + "'");
    }
  }
}

// Header rules that need the whole element list.
void check_elements(const fs::path& path, const Header& h) {
  auto fail = [&](const std::string& why) { fail_input(path.string() + ": PLY header " + why); };
  for (size_t i = 0; i < h.elements.size(); ++i) {
    const Element& e = h.elements[i];
    if (e.count > 0 && e.properties.empty()) fail("declares " + std::to_string(e.count) + " '" + e.name + "' elements without properties");
    if (e.count == 0 || assimp_reads(e.name)) continue;
    for (size_t j = i + 1; j < h.elements.size(); ++j)
      if (h.elements[j].count > 0 && assimp_reads(h.elements[j].name))
        fail("has '" + e.name + "' elements before the '" + h.elements[j].name +
             "' ones; the importer cannot skip elements it does not know (move them to the end)");
  }
}

// assimp reserves what the header declares before reading it, so the counts must fit in
// the bytes after end_header (ASCII: at least "0 " per value; binary: the scalar and
// list-count sizes). Cheap, and names the element before the body walk reads anything.
void check_counts_fit(const fs::path& path, const Header& h, uint64_t body) {
  const uint64_t room = body + (h.ascii ? 1 : 0);  // the last ASCII line may lack its newline
  uint64_t needed = 0;
  for (const Element& e : h.elements) {
    uint64_t per = 0;
    for (const Property& p : e.properties) per += h.ascii ? 2 : uint64_t(p.list ? p.count.bytes : p.value.bytes);
    per = std::max<uint64_t>(per, 1);
    if (e.count > room / per || needed > room - e.count * per)
      fail_input(path.string() + ": PLY header declares " + std::to_string(e.count) + " '" + e.name +
                 "' elements, more than the " + std::to_string(body) + " bytes after end_header can hold");
    needed += e.count * per;
  }
}

// What the walk counts for the limits and checks face lists against.
struct Geometry {
  uint64_t vertices = 0;
  uint64_t triangles = 0;
};

// A face's vertex index list: not empty, at most kMaxFaceVertices long; returns the
// message or "".
std::string index_list_error(const Element& e, uint64_t n) {
  if (n == 0) return "a '" + e.name + "' without vertex indices";
  if (n > uint64_t(kMaxFaceVertices))
    return "a '" + e.name + "' of " + std::to_string(n) + " vertices, more than " + std::to_string(kMaxFaceVertices);
  return "";
}
std::string index_error(const Element& e, int64_t index, const Geometry& g) {
  if (e.name == "tristrips" && index == -1) return "";  // strip restart
  if (index < 0 || uint64_t(index) >= g.vertices)
    return "vertex index " + std::to_string(index) + " out of range (" + std::to_string(g.vertices) + " vertices)";
  return "";
}
void add_triangles(Geometry& g, uint64_t n) { g.triangles += n >= 3 ? n - 2 : 0; }

// An ASCII value of `type`: integers as assimp's strtol10 / strtoul10 read them and in
// the type's range, reals as decimal numbers (fast_atoreal_move throws on anything else).
bool parse_integer(std::string_view word, const ScalarType& type, int64_t& value) {
  bool negative = false;
  if (!word.empty() && (word[0] == '-' || word[0] == '+') && type.min < 0) {
    negative = word[0] == '-';
    word.remove_prefix(1);
  }
  uint64_t magnitude = 0;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), magnitude);
  if (word.empty() || ec != std::errc() || end != word.data() + word.size() || magnitude > uint64_t(INT64_MAX)) return false;
  value = negative ? -int64_t(magnitude) : int64_t(magnitude);
  return value >= type.min && value <= type.max;
}
bool is_real(std::string_view word) {
  size_t i = 0;
  auto digits = [&] {
    const size_t from = i;
    while (i < word.size() && word[i] >= '0' && word[i] <= '9') ++i;
    return i - from;
  };
  if (i < word.size() && (word[i] == '-' || word[i] == '+')) ++i;
  size_t mantissa = digits();
  if (i < word.size() && word[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < word.size() && (word[i] == 'e' || word[i] == 'E')) {
    ++i;
    if (i < word.size() && (word[i] == '-' || word[i] == '+')) ++i;
    if (digits() == 0) return false;
  }
  return i == word.size();
}

// ASCII: one instance per line, as assimp reads them (its line reader also cuts lines at
// NUL, CR and FF and skips some empty lines, so those are refused rather than modelled).
void walk_ascii(const fs::path& path, const Header& h, Geometry& g) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(std::streamoff(h.body_offset));
  uint64_t number = 0;
  std::string line;
  auto fail = [&](const std::string& why) {
    fail_input(path.string() + ": PLY body line " + std::to_string(number) + " " + why);
  };
  auto next_line = [&]() -> bool {
    if (!std::getline(in, line)) return false;
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    for (char c : line)
      if (!(c == '\t' || (c >= ' ' && c <= '~'))) fail("is not ASCII text");
    return true;
  };
  std::vector<std::string_view> words;
  for (const Element& e : h.elements) {
    for (uint64_t i = 0; i < e.count; ++i) {
      if (!next_line()) {
        ++number;
        fail("is missing: the header declares " + std::to_string(e.count) + " '" + e.name + "' elements");
      }
      words.clear();
      for (size_t at = line.find_first_not_of(" \t"); at != std::string::npos; at = line.find_first_not_of(" \t", at)) {
        const size_t end = std::min(line.find_first_of(" \t", at), line.size());
        words.push_back(std::string_view(line).substr(at, end - at));
        at = end;
      }
      if (words.empty()) fail("is empty, a '" + e.name + "' element expected");
      size_t w = 0;
      auto value = [&](const ScalarType& type, int64_t& integer) {
        if (w >= words.size()) fail("has fewer values than its '" + e.name + "' element declares");
        const std::string_view word = words[w++];
        if (type.integer ? !parse_integer(word, type, integer) : !is_real(word))
          fail("has '" + std::string(word.substr(0, 20)) + "' where " + (type.integer ? "an integer" : "a number") +
               " in the range of its type is expected");
      };
      for (const Property& p : e.properties) {
        int64_t n = 1;
        if (p.list) value(p.count, n);
        if (is_index_list(e, p)) {
          if (const std::string why = index_list_error(e, uint64_t(n)); !why.empty()) fail("has " + why);
          add_triangles(g, uint64_t(n));
        }
        for (int64_t k = 0; k < n; ++k) {
          int64_t index = 0;
          value(p.value, index);
          if (is_index_list(e, p))
            if (const std::string why = index_error(e, index, g); !why.empty()) fail("has " + why);
        }
      }
      if (w != words.size()) fail("has more values than its '" + e.name + "' element declares");
    }
    if (e.name == "vertex") g.vertices = e.count;
  }
  while (next_line())
    if (line.find_first_not_of(" \t") != std::string::npos) fail("follows the last element");
}

// Binary: list counts read and checked against the bytes left, index lists read, every
// other value skipped.
void walk_binary(const fs::path& path, const Header& h, uint64_t body, Geometry& g) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(std::streamoff(h.body_offset));
  uint64_t left = body;
  const Element* element = nullptr;
  uint64_t instance = UINT64_MAX;  // UINT64_MAX: the element's records as a whole
  auto fail = [&](const std::string& why) {
    const std::string where = instance == UINT64_MAX ? "'" + element->name + "' elements"
                                                     : "'" + element->name + "' " + std::to_string(instance);
    fail_input(path.string() + ": PLY body, " + where + ": " + why);
  };
  auto skip = [&](uint64_t bytes) {
    if (bytes > left) fail("the file ends " + std::to_string(bytes - left) + " bytes early");
    in.seekg(std::streamoff(bytes), std::ios::cur);
    left -= bytes;
  };
  std::vector<unsigned char> buffer;
  auto read_integers = [&](const ScalarType& type, uint64_t n, std::vector<int64_t>& out) {
    if (n > left / uint64_t(type.bytes))
      fail("a list of " + std::to_string(n) + " entries, more than the " + std::to_string(left) + " bytes left hold");
    buffer.resize(size_t(n) * size_t(type.bytes));
    in.read(reinterpret_cast<char*>(buffer.data()), std::streamsize(buffer.size()));
    left -= buffer.size();
    out.resize(size_t(n));
    for (size_t k = 0; k < out.size(); ++k) {
      uint64_t u = 0;
      for (int b = 0; b < type.bytes; ++b) {
        const int shift = h.big_endian ? 8 * (type.bytes - 1 - b) : 8 * b;
        u |= uint64_t(buffer[k * size_t(type.bytes) + size_t(b)]) << shift;
      }
      if (type.min < 0 && type.bytes < 8 && (u >> (8 * type.bytes - 1)) != 0) u |= ~uint64_t(0) << (8 * type.bytes);  // sign
      out[k] = int64_t(u);
    }
  };
  std::vector<int64_t> values;
  for (const Element& e : h.elements) {
    element = &e;
    instance = UINT64_MAX;
    const bool has_list = std::any_of(e.properties.begin(), e.properties.end(), [](const Property& p) { return p.list; });
    if (!has_list) {  // fixed-size records: one skip
      uint64_t record = 0;
      for (const Property& p : e.properties) record += uint64_t(p.value.bytes);
      if (e.count > 0 && record > 0 && e.count > left / record) fail("the file ends before the last one");
      skip(e.count * record);
    } else {
      for (uint64_t i = 0; i < e.count; ++i) {
        instance = i;
        for (const Property& p : e.properties) {
          if (!p.list) {
            skip(uint64_t(p.value.bytes));
            continue;
          }
          read_integers(p.count, 1, values);
          const int64_t n = values[0];
          if (n < 0) fail("a list count of " + std::to_string(n));
          if (!is_index_list(e, p)) {
            if (uint64_t(n) > left / uint64_t(p.value.bytes))
              fail("a list of " + std::to_string(n) + " entries, more than the " + std::to_string(left) + " bytes left hold");
            skip(uint64_t(n) * uint64_t(p.value.bytes));
            continue;
          }
          if (const std::string why = index_list_error(e, uint64_t(n)); !why.empty()) fail(why);
          read_integers(p.value, uint64_t(n), values);
          for (const int64_t index : values)
            if (const std::string why = index_error(e, index, g); !why.empty()) fail(why);
          add_triangles(g, uint64_t(n));
        }
      }
    }
    if (e.name == "vertex") g.vertices = e.count;
  }
}

}  // namespace

void check_ply_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(64 * 1024, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  std::string magic = head.substr(0, 3);
  for (char& c : magic) c = char(std::tolower(static_cast<unsigned char>(c)));  // assimp ignores case
  const std::string ext = lowercase_extension(path);
  if (magic != "ply" && ext != ".ply") return;
  if (magic != "ply") fail_input(path.string() + ": PLY header does not start with the line 'ply'");
  const Header h = parse_header(path, head);
  check_elements(path, h);
  std::error_code ec;
  const uintmax_t size = fs::file_size(path, ec);
  const uint64_t body = ec || size < h.body_offset ? 0 : uint64_t(size - h.body_offset);
  check_counts_fit(path, h, body);
  Geometry g;
  for (const Element& e : h.elements)
    if (e.name == "vertex") check_geometry_budget(path.string(), 0, e.count);
  if (h.ascii)
    walk_ascii(path, h, g);
  else
    walk_binary(path, h, body, g);
  check_geometry_budget(path.string(), g.triangles, g.vertices);
}

}  // namespace proxima
