// Serialization of the winged-pair structure (Funkhouser, section 3: "converted to an ASCII
// representation and written to a file for use by later phases").
#include "proxima/visibility/winged_pair_io.h"

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
  Reader(std::istream& in, const std::filesystem::path& path) : in_(in), path_(path) {}

  void expect(const std::string& word) {
    std::string w;
    if (!(in_ >> w) || w != word) fail("expected '" + word + "'");
  }
  double real() {
    double x;
    if (!(in_ >> x)) fail("truncated or non-numeric field");
    return x;
  }
  size_t count() {
    long long x;
    if (!(in_ >> x) || x < 0 || x > (1ll << 31)) fail("bad count");
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
};

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
  Reader r(in, path);
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
  wp.vertices.resize(r.count());
  for (Vertex& v : wp.vertices) {
    v.position = {r.real(), r.real(), r.real()};
    v.edge = r.index(1ull << 31, true);
  }
  r.expect("edges");
  wp.edges.resize(r.count());
  for (Edge& e : wp.edges) {
    e.vertex[0] = r.index(wp.vertices.size());
    e.vertex[1] = r.index(wp.vertices.size());
    e.pair = r.index(1ull << 31);
  }
  r.expect("faces");
  wp.faces.resize(r.count());
  for (Face& f : wp.faces) {
    f.cell[0] = r.index(1ull << 31, true);
    f.cell[1] = r.index(1ull << 31, true);
    f.pair = r.index(1ull << 31);
    f.polygon = r.index(wp.polygon_count, true);
    f.plane.normal = {r.real(), r.real(), r.real()};
    f.plane.offset = r.real();
  }
  r.expect("cells");
  wp.cells.resize(r.count());
  for (Cell& c : wp.cells) c.face = r.index(wp.faces.size(), true);
  r.expect("pairs");
  wp.pairs.resize(r.count());
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
  if (!finalize(wp)) r.fail("clock links do not close around a face");
  return wp;
}

}  // namespace proxima::visibility
