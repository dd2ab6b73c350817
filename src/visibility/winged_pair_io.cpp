// Serialization of the winged-pair structure (Funkhouser, section 3: "converted to an ASCII
// representation and written to a file for use by later phases").
#include "proxima/visibility/winged_pair_io.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"

namespace proxima::visibility {
namespace {

std::string ref(uint32_t x) { return x == kNone ? "-1" : std::to_string(x); }

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

class Reader {
 public:
  Reader(std::istream& in, const std::filesystem::path& path, uintmax_t bytes)
      : in_(in), path_(path), bytes_(bytes) {}

  void expect(const std::string& word) {
    std::string w;
    if (!(in_ >> w) || w != word) fail("expected '" + word + "'");
  }
  // Finite, and small enough that coordinates, squared, stay finite in the tracer.
  double real() {
    double x;
    if (!(in_ >> x)) fail("truncated or non-numeric field");
    if (!(std::abs(x) <= 1e100)) fail("number out of range");
    return x;
  }
  // A record count; each record takes at least `record_bytes` of the file (fields of at
  // least one digit and a separator), so a count the file cannot hold is refused before
  // anything is allocated for it.
  size_t count(size_t record_bytes = 1) {
    long long x;
    if (!(in_ >> x) || x < 0 || x > (1ll << 31)) fail("bad count");
    if (uintmax_t(x) > bytes_ / record_bytes)
      fail("count " + std::to_string(x) + " is more than the file can hold");
    return size_t(x);
  }
  // Index below `limit`, or kNone written as −1 when `optional`.
  uint32_t index(size_t limit, bool optional = false) {
    long long x;
    if (!(in_ >> x)) fail("truncated or non-numeric field");
    if (x == -1 && optional) return kNone;
    if (x < 0 || size_t(x) >= limit) fail("reference " + std::to_string(x) + " out of range");
    return uint32_t(x);
  }
  [[noreturn]] void fail(const std::string& what) {
    fail_input(path_.string() + ": malformed winged-pair file: " + what);
  }

 private:
  std::istream& in_;
  const std::filesystem::path& path_;
  uintmax_t bytes_;
};

// Every pair link, and the spin cycle of every edge, closes: the traversals in
// finalize() and visibility_map.cpp (silhouette test) walk them until they return.
// Empty string when they do.
std::string link_error(const WingedPair& wp) {
  const size_t np = wp.pairs.size();
  for (size_t p = 0; p < np; ++p) {
    const Pair& pr = wp.pairs[p];
    if (wp.pairs[pr.clock[0]].clock[1] != p || wp.pairs[pr.spin[0]].spin[1] != p)
      return "pair " + std::to_string(p) + ": clock or spin links are not mutual";
    if (wp.pairs[pr.clock[0]].face != pr.face) return "pair " + std::to_string(p) + ": clock link leaves its face";
    if (wp.pairs[pr.spin[0]].edge != pr.edge) return "pair " + std::to_string(p) + ": spin link leaves its edge";
  }
  // With mutual links every pair lies on one spin cycle, all of one edge; each edge's
  // cycle must be reached from its own pair.
  for (size_t e = 0; e < wp.edges.size(); ++e)
    if (wp.pairs[wp.edges[e].pair].edge != e) return "edge " + std::to_string(e) + ": its pair is on another edge";
  for (size_t f = 0; f < wp.faces.size(); ++f)
    if (wp.pairs[wp.faces[f].pair].face != f) return "face " + std::to_string(f) + ": its pair is on another face";
  return {};
}

}  // namespace

void save_winged_pair(const std::filesystem::path& path, const WingedPair& wp) {
  std::ostringstream o;
  o << "proxima-winged-pair 1\nscale " << num(wp.scale) << " polygons " << wp.polygon_count << "\n";
  o << "vertices " << wp.vertices.size() << "\n";
  for (const Vertex& v : wp.vertices)
    o << num(v.position.x) << ' ' << num(v.position.y) << ' ' << num(v.position.z) << ' ' << ref(v.edge) << "\n";
  o << "edges " << wp.edges.size() << "\n";
  for (const Edge& e : wp.edges) o << e.vertex[0] << ' ' << e.vertex[1] << ' ' << e.pair << "\n";
  o << "faces " << wp.faces.size() << "\n";
  for (const Face& f : wp.faces)
    o << ref(f.cell[0]) << ' ' << ref(f.cell[1]) << ' ' << f.pair << ' ' << ref(f.polygon) << ' '
      << num(f.plane.normal.x) << ' ' << num(f.plane.normal.y) << ' ' << num(f.plane.normal.z) << ' '
      << num(f.plane.offset) << "\n";
  o << "cells " << wp.cells.size() << "\n";
  for (const Cell& c : wp.cells) o << ref(c.face) << "\n";
  o << "pairs " << wp.pairs.size() << "\n";
  for (const Pair& p : wp.pairs)
    o << p.face << ' ' << p.edge << ' ' << p.clock[0] << ' ' << p.clock[1] << ' ' << p.spin[0] << ' '
      << p.spin[1] << ' ' << int(p.direction) << "\n";
  write_text_file(path, o.str());
}

WingedPair load_winged_pair(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) fail_input(path.string() + ": cannot open winged-pair file");
  std::error_code ec;
  const uintmax_t bytes = std::filesystem::file_size(path, ec);
  Reader r(in, path, ec ? 0 : bytes);
  WingedPair wp;
  r.expect("proxima-winged-pair");
  r.expect("1");
  r.expect("scale");
  wp.scale = r.real();
  if (!(wp.scale > 0.0)) r.fail("scale must be positive");
  r.expect("polygons");
  wp.polygon_count = uint32_t(r.count());
  // Counts come first in each section; references into later sections are checked after.
  r.expect("vertices");
  wp.vertices.resize(r.count(8));
  for (Vertex& v : wp.vertices) {
    v.position = {r.real(), r.real(), r.real()};
    v.edge = r.index(1ull << 31, true);
  }
  r.expect("edges");
  wp.edges.resize(r.count(6));
  for (Edge& e : wp.edges) {
    e.vertex[0] = r.index(wp.vertices.size());
    e.vertex[1] = r.index(wp.vertices.size());
    e.pair = r.index(1ull << 31);
  }
  r.expect("faces");
  wp.faces.resize(r.count(16));
  for (Face& f : wp.faces) {
    f.cell[0] = r.index(1ull << 31, true);
    f.cell[1] = r.index(1ull << 31, true);
    f.pair = r.index(1ull << 31);
    f.polygon = r.index(wp.polygon_count, true);
    f.plane.normal = {r.real(), r.real(), r.real()};
    f.plane.offset = r.real();
    if (std::abs(glm::length(f.plane.normal) - 1.0) > 1e-6) r.fail("face normal is not unit length");
  }
  r.expect("cells");
  wp.cells.resize(r.count(2));
  for (Cell& c : wp.cells) c.face = r.index(wp.faces.size(), true);
  r.expect("pairs");
  wp.pairs.resize(r.count(14));
  for (Pair& p : wp.pairs) {
    p.face = r.index(wp.faces.size());
    p.edge = r.index(wp.edges.size());
    for (uint32_t& x : p.clock) x = r.index(wp.pairs.size());
    for (uint32_t& x : p.spin) x = r.index(wp.pairs.size());
    p.direction = uint8_t(r.index(2));
  }
  for (const Vertex& v : wp.vertices)
    if (v.edge != kNone && v.edge >= wp.edges.size()) r.fail("vertex edge out of range");
  for (const Edge& e : wp.edges)
    if (e.pair >= wp.pairs.size()) r.fail("edge pair out of range");
  for (const Face& f : wp.faces)
    if (f.pair >= wp.pairs.size() || (f.cell[0] != kNone && f.cell[0] >= wp.cells.size()) ||
        (f.cell[1] != kNone && f.cell[1] >= wp.cells.size()))
      r.fail("face reference out of range");
  if (const std::string why = link_error(wp); !why.empty()) r.fail(why);
  if (!finalize(wp)) r.fail("clock links do not close around a face");
  return wp;
}

}  // namespace proxima::visibility
