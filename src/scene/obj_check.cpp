// OBJ index validation before assimp (obj_check.h).
#include "proxima/scene/obj_check.h"

#include <cctype>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>

#include "proxima/core/error.h"
#include "proxima/core/file_extension.h"

namespace proxima {
namespace fs = std::filesystem;

namespace {

// One kind of indexed element (vertices, texture coordinates, normals): how many the file
// has so far, and the extreme 0-based indices the faces refer to.
struct IndexedKind {
  const char* name;
  int64_t count = 0;
  bool referred = false;
  int64_t min_index = 0, max_index = 0;
  int64_t line_of_min = 0, line_of_max = 0;

  void refer(int64_t one_based, int64_t line) {
    // Negative = relative to the elements read so far (assimp: size + value).
    const int64_t index = one_based > 0 ? one_based - 1 : count + one_based;
    if (!referred || index < min_index) min_index = index, line_of_min = line;
    if (!referred || index > max_index) max_index = index, line_of_max = line;
    referred = true;
  }
};

// assimp's OBJ tokens are separated by spaces and tabs only.
bool is_space(char c) { return c == ' ' || c == '\t'; }

bool starts_case_blind(std::string_view s, std::string_view lower) {
  if (s.size() < lower.size()) return false;
  for (size_t i = 0; i < lower.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[i])) != lower[i]) return false;
  return true;
}

// Numeric components of a `v` line after the keyword, counted as assimp 5.2 does
// (ObjFileParser::getNumComponentsInDataDefinition): whitespace-separated tokens starting
// with a digit, sign or point, or with nan / inf. assimp adds a vertex only for 3, 4 or 6.
int vertex_components(std::string_view rest) {
  int n = 0;
  size_t i = 0;
  while (i < rest.size()) {
    while (i < rest.size() && is_space(rest[i])) ++i;
    if (i >= rest.size()) break;
    const char c = rest[i];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.' ||
        starts_case_blind(rest.substr(i), "nan") || starts_case_blind(rest.substr(i), "inf"))
      ++n;
    while (i < rest.size() && !is_space(rest[i])) ++i;
  }
  return n;
}


void check_line(std::string_view line, int64_t line_no, IndexedKind (&kinds)[3], const fs::path& path) {
  if (line.empty()) return;
  const char c0 = line[0];
  if (c0 == 'v' && line.size() > 1) {
    if (is_space(line[1])) {
      const int n = vertex_components(line.substr(1));
      if (n == 3 || n == 4 || n == 6) ++kinds[0].count;
    } else if (line[1] == 't') {
      ++kinds[1].count;
    } else if (line[1] == 'n') {
      ++kinds[2].count;
    }
    return;
  }
  if (c0 != 'f' && c0 != 'l' && c0 != 'p') return;
  size_t i = 0;
  while (i < line.size() && !is_space(line[i])) ++i;  // the keyword
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    if (i >= line.size() || line[i] == '#') break;
    size_t end = i;
    while (end < line.size() && !is_space(line[end])) ++end;
    const std::string_view token = line.substr(i, end - i);
    int part = 0;  // v / t / n, as assimp counts the slashes
    for (size_t p = 0; p <= token.size() && part < 3; ++part) {
      size_t q = token.find('/', p);
      if (q == std::string_view::npos) q = token.size();
      std::string_view field = token.substr(p, q - p);
      if (!field.empty() && field[0] == '+') field.remove_prefix(1);  // atoi accepts it
      int64_t value = 0;
      const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
      if (ec == std::errc() && ptr != field.data()) {
        if (part == 0 && value == 0)
          fail_input(path.string() + ": line " + std::to_string(line_no) + ": OBJ vertex index 0 (indices start at 1)");
        if (value != 0) kinds[part].refer(value, line_no);
      }
      p = q + 1;
    }
    i = end;
  }
}

}  // namespace

void check_obj_indices(const fs::path& path) {
  if (lowercase_extension(path) != ".obj") return;
  std::ifstream in(path, std::ios::binary);
  IndexedKind kinds[3] = {{"vertex"}, {"texture coordinate"}, {"normal"}};
  std::string text;
  int64_t line_no = 0;  // counted by '\n', for messages
  while (std::getline(in, text)) {
    ++line_no;
    // assimp also ends a line at '\r', '\0' and '\f' (IOStreamBuffer::getNextLine).
    size_t start = 0;
    while (start <= text.size()) {
      size_t stop = text.find_first_of(std::string_view("\r\0\f", 3), start);
      if (stop == std::string::npos) stop = text.size();
      check_line(std::string_view(text).substr(start, stop - start), line_no, kinds, path);
      start = stop + 1;
    }
  }
  for (int k = 0; k < 3; ++k) {
    const IndexedKind& kind = kinds[k];
    if (!kind.referred) continue;
    if (k > 0 && kind.count == 0) continue;         // assimp ignores t / n indices then
    if (kind.min_index < 0)
      fail_input(path.string() + ": line " + std::to_string(kind.line_of_min) + ": OBJ " + kind.name +
                 " index refers before the first " + kind.name);
    if (kind.max_index >= kind.count)
      fail_input(path.string() + ": line " + std::to_string(kind.line_of_max) + ": OBJ " + kind.name + " index " +
                 std::to_string(kind.max_index + 1) + " out of range (the file has " + std::to_string(kind.count) +
                 ")");
  }
}

}  // namespace proxima
