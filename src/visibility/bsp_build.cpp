// Spatial subdivision of Funkhouser, "A visibility algorithm for hybrid geometry- and
// image-based modeling and rendering" (Computers & Graphics 1999), section 3: a BSP whose
// cells are split by the planes of input polygons, maintained as a winged-pair cell complex.
//
// Symbols: a cell C is split by the plane H of a polygon P; faces of C crossing H are split
// along H ∩ face (their crossing edges split globally, so neighbor cells keep a conforming
// boundary); the new face S = C ∩ H separates the two child cells; the fragments of input
// polygons lying on H subdivide S into faces "entirely inside or outside every input
// polygon" (opaque, labeled with the polygon, or transparent). Recursion ends when no
// polygon fragment intersects a cell's interior. Split-plane choice follows Naylor's
// scoring (paper ref. [29]): among evenly spaced candidate polygons of a cell, the plane
// minimizing split_weight · (fragments split) + |front − back|.
//
// Robustness (docs/visibility.md, "Robustness rules"): planes are canonical (input planes
// and carve lines within the snap tolerance share one id, input fragments are projected
// onto theirs); a vertex is on every plane it was made on exactly (membership, no
// arithmetic), on any other within eps = options.epsilon · scale; each vertex is classified
// once per plane (stamped cache), so faces sharing a vertex never disagree. A split whose
// classification is not a convex cut is retried with exact sides, then (a plane of the
// cell's fragments) moved by a few tolerances, then other planes and auxiliary planes;
// fragments are never dropped while a plane can place them; a cell no plane can cut is
// sealed (made opaque), and what is left is counted.
#include "proxima/visibility/bsp_build.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <unordered_map>
#include <utility>

#include "proxima/core/timer.h"

namespace proxima::visibility {
namespace {

uint64_t edge_key(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
}

struct BuildFace {
  std::vector<uint32_t> loop;  // vertex ids, counter-clockwise seen from the front
  Plane plane;
  uint32_t plane_id = kNone;   // canonical plane (planes_) the face lies on
  uint32_t cell[2] = {kNone, kNone};
  uint32_t polygon = kNone;
};

struct Fragment {
  std::vector<dvec3> v;  // convex, the input polygon's winding
  uint32_t polygon = kNone;
};

enum class Pattern { kFront, kBack, kCrossing, kInvalid };

// The outcome of cutting a cell by one candidate plane (Builder::cut_by).
struct Cut {
  uint32_t face = kNone;   // the new separating face; kNone when the cell was not split
  uint32_t back = kNone;   // the new back cell
  uint32_t plane = kNone;  // the plane that split it: the candidate or a shifted copy of it
  bool boundary = false;   // the cell lies on one side of the candidate within the tolerance
  std::vector<uint32_t> on;  // then: the cell's faces on the candidate
};

// Shifts of a fragment's plane tried when the plane itself cannot cut a cell, in units of
// the plane tolerance eps: at most 256 · eps (2.56e-6 · scale at the default epsilon), well
// inside the snap tolerance. ≥ 4 · eps, so that no vertex on the unshifted plane is on the
// shifted one within the tolerance.
constexpr double kShifts[] = {4.0, 16.0, 64.0, 256.0};

class Builder {
 public:
  Builder(const ModelPolygons& model, const BspOptions& options, BspStats& stats)
      : model_(model), options_(options), stats_(stats),
        eps_(options.epsilon * model.scale),
        eps_area_(1e-3 * eps_ * eps_) {}

  WingedPair run();

 private:
  uint32_t add_vertex(const dvec3& p, std::vector<uint32_t> on_planes) {
    verts_.push_back(p);
    side_.push_back(0);
    stamp_of_.push_back(stamp_);
    vplanes_.push_back(std::move(on_planes));
    return uint32_t(verts_.size() - 1);
  }

  bool on_plane(uint32_t v, uint32_t id) const {
    return std::find(vplanes_[v].begin(), vplanes_[v].end(), id) != vplanes_[v].end();
  }

  // Side of vertex v of the current plane (classified once per plane, then cached): 0 when
  // the vertex was made on that canonical plane (exact, no arithmetic), else by distance.
  int8_t side(uint32_t v) {
    if (stamp_of_[v] != stamp_) {
      if (on_plane(v, plane_id_)) {
        side_[v] = 0;
      } else {
        const double d = plane_.distance(verts_[v]), tol = tol_scale_ * eps_;
        side_[v] = d > tol ? 1 : (d < -tol ? -1 : 0);
      }
      stamp_of_[v] = stamp_;
    }
    return side_[v];
  }

  // tol_scale multiplies the tolerance: 1 = the plane tolerance; 0 = exact sides (a vertex
  // not made on the plane is on it only at distance exactly 0), the fallback when the
  // tolerance classifies a cell or face inconsistently.
  void begin_plane(const Plane& h, uint32_t id, double tol_scale = 1.0) {
    plane_ = h;
    plane_id_ = id;
    tol_scale_ = tol_scale;
    ++stamp_;
  }

  // Canonical planes: every plane used (input polygons' and carve lines') is looked up
  // among the earlier ones and shares the id of one passing within the snap tolerance
  // (kSnapTolerance · scale) of its points — coplanar overlapping faces, seams, slightly
  // raised faces, and a carve line on a wall's plane become one plane for every decision.
  uint32_t plane_id(const Plane& h, const std::vector<dvec3>& pts);

  Pattern pattern(uint32_t f);
  void split_edge(uint32_t a, uint32_t b);
  uint32_t split_face(uint32_t f);
  uint32_t split_cell(uint32_t c, uint32_t plane_id, double tol_scale, uint32_t* back_cell, bool* no_cut);
  Cut cut_by(uint32_t c, uint32_t id, bool fragment_plane);
  bool split_shifted(uint32_t c, uint32_t id, int toward, Cut& cut);
  std::vector<uint32_t> faces_on_plane(uint32_t c, uint32_t plane_id);
  void carve(uint32_t s, const std::vector<Fragment>& coplanar);
  void seal(uint32_t c, const std::vector<Fragment>& frags);
  std::vector<uint32_t> rank_splitters(const std::vector<Fragment>& frags);
  void make_box();
  WingedPair export_structure() const;

  const ModelPolygons& model_;
  const BspOptions& options_;
  BspStats& stats_;
  const double eps_, eps_area_;

  std::vector<dvec3> verts_;
  std::vector<int8_t> side_;
  std::vector<uint32_t> stamp_of_;
  std::vector<std::vector<uint32_t>> vplanes_;  // canonical planes each vertex was made on
  uint32_t stamp_ = 1;
  Plane plane_;
  uint32_t plane_id_ = kNone;
  double tol_scale_ = 1.0;
  std::vector<Plane> planes_;          // canonical planes: input clusters, box, carve lines
  std::vector<uint32_t> poly_plane_;   // input polygon → canonical plane id
  std::unordered_map<uint64_t, std::vector<uint32_t>> plane_buckets_;  // by quantized normal, offset
  double offset_cell_ = 1.0;

  std::vector<BuildFace> faces_;
  std::vector<std::vector<uint32_t>> cells_;  // faces of each cell
  std::unordered_map<uint64_t, std::vector<uint32_t>> edge_faces_;
};

// Where face f lies relative to the current plane. A crossing face must meet the plane in
// exactly two points, each a vertex on it between opposite sides or a crossing edge.
Pattern Builder::pattern(uint32_t f) {
  const auto& loop = faces_[f].loop;
  const size_t n = loop.size();
  bool plus = false, minus = false;
  for (uint32_t v : loop) {
    int8_t s = side(v);
    plus |= s > 0;
    minus |= s < 0;
  }

  if (!plus && !minus) return Pattern::kInvalid;
  if (!minus) return Pattern::kFront;
  if (!plus) return Pattern::kBack;
  int meets = 0;
  for (size_t i = 0; i < n; ++i) {
    int8_t s = side(loop[i]), t = side(loop[(i + 1) % n]);
    if (s == 0) {
      int8_t p = side(loop[(i + n - 1) % n]);
      if (p * t >= 0) return Pattern::kInvalid;
      ++meets;
    } else if (s * t < 0) {
      ++meets;
    }
  }
  return meets == 2 ? Pattern::kCrossing : Pattern::kInvalid;
}

// Splits edge (a, b), whose ends lie strictly on opposite sides, at the plane; the new
// vertex enters the loop of every face around the edge (in every cell).
void Builder::split_edge(uint32_t a, uint32_t b) {
  const uint32_t lo = std::min(a, b), hi = std::max(a, b);
  const double dlo = plane_.distance(verts_[lo]), dhi = plane_.distance(verts_[hi]);
  std::vector<uint32_t> on;  // the planes of the edge (shared by both ends) and the cut
  for (uint32_t id : vplanes_[a])
    if (on_plane(b, id)) on.push_back(id);
  on.push_back(plane_id_);
  const uint32_t m = add_vertex(verts_[lo] + (verts_[hi] - verts_[lo]) * (dlo / (dlo - dhi)), std::move(on));
  side_[m] = 0;
  auto node = edge_faces_.extract(edge_key(a, b));
  std::vector<uint32_t> around = node.empty() ? std::vector<uint32_t>{} : std::move(node.mapped());
  for (uint32_t g : around) {
    auto& loop = faces_[g].loop;
    const size_t n = loop.size();
    for (size_t i = 0; i < n; ++i) {
      uint32_t u = loop[i], w = loop[(i + 1) % n];
      if ((u == a && w == b) || (u == b && w == a)) {
        loop.insert(loop.begin() + long(i) + 1, m);
        break;
      }
    }
  }
  edge_faces_[edge_key(a, m)] = around;
  edge_faces_[edge_key(m, b)] = std::move(around);
}

// Splits a crossing face along the plane: f keeps the front part, the returned new face is
// the back part; both keep f's plane, label and cells (the cells gain the new face).
uint32_t Builder::split_face(uint32_t f) {
  std::vector<std::pair<uint32_t, uint32_t>> crossing;
  {
    const auto& loop = faces_[f].loop;
    for (size_t i = 0; i < loop.size(); ++i) {
      uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
      if (side(a) * side(b) < 0) crossing.push_back({a, b});
    }
  }
  for (auto [a, b] : crossing) split_edge(a, b);

  const std::vector<uint32_t> loop = faces_[f].loop;
  const size_t n = loop.size();
  size_t i0 = 0, i1 = 0;  // the vertex on the plane entering the back side / the front side
  for (size_t i = 0; i < n; ++i) {
    if (side(loop[i]) != 0) continue;
    if (side(loop[(i + n - 1) % n]) > 0) i0 = i;
    else i1 = i;
  }
  std::vector<uint32_t> front, back;
  for (size_t i = i1;; i = (i + 1) % n) {
    front.push_back(loop[i]);
    if (i == i0) break;
  }
  for (size_t i = i0;; i = (i + 1) % n) {
    back.push_back(loop[i]);
    if (i == i1) break;
  }
  const uint32_t g = uint32_t(faces_.size());
  BuildFace copy = faces_[f];
  copy.loop = back;
  faces_.push_back(std::move(copy));
  faces_[f].loop = std::move(front);
  for (size_t k = 0; k + 1 < back.size(); ++k) {
    for (uint32_t& x : edge_faces_[edge_key(back[k], back[k + 1])])
      if (x == f) x = g;
  }
  edge_faces_[edge_key(loop[i0], loop[i1])] = {f, g};
  for (uint32_t c : faces_[g].cell)
    if (c != kNone) cells_[c].push_back(g);
  return g;
}

// Splits cell c by plane h. c keeps the front part; *back_cell receives the new back cell.
// Returns the new separating face, or kNone when h does not split c consistently (c may
// then have gained collinear vertices and coplanar face splits, which keep it valid).
uint32_t Builder::split_cell(uint32_t c, uint32_t plane_id, double tol_scale, uint32_t* back_cell, bool* no_cut) {
  const Plane& h = planes_[plane_id];
  begin_plane(h, plane_id, tol_scale);
  const std::vector<uint32_t> original = cells_[c];
  bool plus = false, minus = false;
  for (uint32_t f : original)
    for (uint32_t v : faces_[f].loop) {
      plus |= side(v) > 0;
      minus |= side(v) < 0;
    }
  *no_cut = !plus || !minus;
  if (*no_cut) return kNone;

  auto in_cell = [&](uint32_t f) { return faces_[f].cell[0] == c || faces_[f].cell[1] == c; };
  std::vector<Pattern> patterns;
  for (uint32_t f : original) {
    patterns.push_back(pattern(f));
    if (patterns.back() == Pattern::kInvalid) {
      ++stats_.rejected_planes;
      return kNone;
    }
  }
  // Cross-section edges already on the plane: between a front and a back face of c.
  std::vector<std::pair<uint32_t, uint32_t>> section;
  for (size_t i = 0; i < original.size(); ++i) {
    if (patterns[i] == Pattern::kCrossing) continue;
    const auto& loop = faces_[original[i]].loop;
    for (size_t k = 0; k < loop.size(); ++k) {
      uint32_t a = loop[k], b = loop[(k + 1) % loop.size()];
      if (side(a) != 0 || side(b) != 0) continue;
      for (uint32_t g : edge_faces_[edge_key(a, b)]) {
        if (g == original[i] || !in_cell(g)) continue;
        auto it = std::find(original.begin(), original.end(), g);
        if (it == original.end()) continue;
        Pattern pg = patterns[size_t(it - original.begin())];
        if (pg == patterns[i] || pg == Pattern::kCrossing) {
          ++stats_.rejected_planes;
          return kNone;
        }
        if (patterns[i] == Pattern::kFront) section.push_back({a, b});
      }
    }
  }
  for (size_t i = 0; i < original.size(); ++i) {
    if (patterns[i] != Pattern::kCrossing) continue;
    uint32_t g = split_face(original[i]);
    section.push_back({faces_[g].loop.front(), faces_[g].loop.back()});
  }

  // Chain the cross-section edges into one loop.
  std::unordered_map<uint32_t, std::pair<uint32_t, uint32_t>> next;
  for (auto [a, b] : section) {
    for (auto [u, w] : {std::pair{a, b}, std::pair{b, a}}) {
      auto [it, fresh] = next.try_emplace(u, w, kNone);
      if (!fresh) {
        if (it->second.second != kNone) {
          ++stats_.rejected_planes;
          return kNone;
        }
        it->second.second = w;
      }
    }
  }
  std::vector<uint32_t> loop;
  const uint32_t start = section.empty() ? kNone : section.front().first;
  uint32_t prev = kNone, cur = start;
  while (cur != kNone && loop.size() <= section.size()) {
    loop.push_back(cur);
    auto [p, q] = next[cur];
    prev = std::exchange(cur, (p == kNone || q == kNone) ? kNone : (p != prev ? p : q));
    if (cur == start) break;
  }
  if (loop.size() < 3 || loop.size() != section.size() || cur != start) {
    ++stats_.rejected_planes;
    return kNone;
  }
  std::vector<dvec3> pts;
  for (uint32_t v : loop) pts.push_back(verts_[v]);
  if (glm::dot(newell_normal(pts), h.normal) < 0.0) std::reverse(loop.begin(), loop.end());

  // Partition the faces of c; the back ones move to the new cell.
  const uint32_t back = uint32_t(cells_.size());
  cells_.emplace_back();
  std::vector<uint32_t> front_faces;
  for (uint32_t f : cells_[c]) {
    bool is_back = false;
    for (uint32_t v : faces_[f].loop)
      if (side(v) != 0) {
        is_back = side(v) < 0;
        break;
      }
    if (is_back) {
      for (uint32_t& x : faces_[f].cell)
        if (x == c) x = back;
      cells_[back].push_back(f);
    } else {
      front_faces.push_back(f);
    }
  }
  cells_[c] = std::move(front_faces);

  // The cross-section's vertices are on h from now on, for every later decision.
  for (uint32_t v : loop)
    if (!on_plane(v, plane_id)) vplanes_[v].push_back(plane_id);
  const uint32_t s = uint32_t(faces_.size());
  BuildFace face;
  face.loop = std::move(loop);
  face.plane = h;
  face.plane_id = plane_id;
  face.cell[0] = back;
  face.cell[1] = c;
  for (size_t k = 0; k < face.loop.size(); ++k)
    edge_faces_[edge_key(face.loop[k], face.loop[(k + 1) % face.loop.size()])].push_back(s);
  faces_.push_back(std::move(face));
  cells_[c].push_back(s);
  cells_[back].push_back(s);
  *back_cell = back;
  return s;
}

// Cuts cell c by candidate plane id: by the plane tolerance, else by exact sides. A plane of
// the cell's fragments (fragment_plane) that cuts the cell inconsistently at both, or that
// leaves the cell on one side without a face of the cell on it, is tried shifted
// (split_shifted): the inconsistency comes from a near-degenerate spot of the cell at the
// plane — an edge shorter than the tolerance with both ends on the plane, so of arbitrary
// direction; a face meeting the plane along several vertices within the tolerance — that a
// parallel plane a few tolerances away misses.
Cut Builder::cut_by(uint32_t c, uint32_t id, bool fragment_plane) {
  Cut cut;
  bool no_cut = false;
  for (double t : {1.0, 0.0})
    if (cut.face == kNone && !no_cut) cut.face = split_cell(c, id, t, &cut.back, &no_cut);
  if (cut.face != kNone) {
    cut.plane = id;
    return cut;
  }
  if (no_cut) {
    cut.on = faces_on_plane(c, id);
    if (!cut.on.empty() || !fragment_plane) {
      cut.boundary = true;
      return cut;
    }
    // The cell touches the plane (within the tolerance) but has no face on it: the
    // fragments lie inside the cell, which the plane shifted toward the cell cuts.
    begin_plane(planes_[id], id);
    int toward = 0;
    for (uint32_t f : cells_[c])
      for (uint32_t v : faces_[f].loop) toward = side(v) != 0 ? side(v) : toward;
    if (toward == 0 || !split_shifted(c, id, toward, cut)) cut.boundary = true;
    return cut;
  }
  if (fragment_plane) split_shifted(c, id, 0, cut);
  return cut;
}

// Splits cell c by plane id moved along its normal by k · eps for k in kShifts (toward > 0:
// forward only, < 0: backward only, 0: forward then backward at each k). The shifted plane
// is a new canonical plane no other polygon snaps to (it is not entered in the lookup).
bool Builder::split_shifted(uint32_t c, uint32_t id, int toward, Cut& cut) {
  for (double k : kShifts)
    for (int sign : {1, -1}) {
      if (toward * sign < 0) continue;
      Plane h = planes_[id];
      h.offset -= double(sign) * k * eps_;
      const uint32_t shifted = uint32_t(planes_.size());
      planes_.push_back(h);
      bool no_cut = false;
      cut.face = split_cell(c, shifted, 1.0, &cut.back, &no_cut);
      if (cut.face != kNone) {
        cut.plane = shifted;
        ++stats_.shifted_splits;
        return true;
      }
    }
  return false;
}

// No plane of the cell's fragments (nor an auxiliary plane) cuts cell c consistently: the
// cell is sealed. Its transparent faces become opaque, labeled with the polygon of its
// largest fragment, so no sightline passes through the cell and every one that could
// meet a fragment in it is blocked: conservative (the cell's outline is over-covered),
// never a hole. Counted, with the largest sealed cell's bounding-box diagonal.
void Builder::seal(uint32_t c, const std::vector<Fragment>& frags) {
  const Fragment* largest = &frags.front();
  double best = -1.0;
  for (const Fragment& f : frags) {
    const double a = glm::length(newell_normal(f.v));
    if (a > best) {
      best = a;
      largest = &f;
    }
  }
  dvec3 lo(INFINITY), hi(-INFINITY);
  for (uint32_t f : cells_[c]) {
    if (faces_[f].polygon == kNone) faces_[f].polygon = largest->polygon;
    for (uint32_t v : faces_[f].loop) {
      lo = glm::min(lo, verts_[v]);
      hi = glm::max(hi, verts_[v]);
    }
  }
  ++stats_.sealed_cells;
  stats_.sealed_fragments += frags.size();
  if (!cells_[c].empty()) stats_.sealed_extent = std::max(stats_.sealed_extent, glm::length(hi - lo));
}

// The faces of cell c lying on the plane (every vertex on it).
std::vector<uint32_t> Builder::faces_on_plane(uint32_t c, uint32_t plane_id) {
  begin_plane(planes_[plane_id], plane_id);
  std::vector<uint32_t> out;
  for (uint32_t f : cells_[c]) {
    bool on = true;
    for (uint32_t v : faces_[f].loop) on &= side(v) == 0;
    if (on) out.push_back(f);
  }
  return out;
}

// Subdivides the new face s by the edge lines of the fragments lying on its plane: the
// pieces inside a fragment become opaque faces of its polygon (the first polygon wins
// where coplanar polygons overlap).
void Builder::carve(uint32_t s, const std::vector<Fragment>& coplanar) {
  std::vector<uint32_t> pieces = {s};
  for (const Fragment& frag : coplanar) {
    std::vector<uint32_t> inside;
    for (uint32_t p : pieces)
      if (faces_[p].polygon == kNone) inside.push_back(p);
    const dvec3 n = glm::normalize(newell_normal(frag.v));
    for (size_t k = 0; k < frag.v.size() && !inside.empty(); ++k) {
      const dvec3& a = frag.v[k];
      const dvec3& b = frag.v[(k + 1) % frag.v.size()];
      dvec3 out = glm::cross(b - a, n);  // outward in the fragment's plane
      double len = glm::length(out);
      if (len <= eps_area_) continue;
      Plane e{out / len, -glm::dot(out / len, a)};
      // The canonical plane (vertices made on it lie on it), oriented as this fragment's line.
      const uint32_t id = plane_id(e, {a, b});
      Plane q = planes_[id];
      if (glm::dot(q.normal, e.normal) < 0.0) q = {-q.normal, -q.offset};
      begin_plane(q, id);
      std::vector<uint32_t> kept;
      for (uint32_t p : inside) {
        Pattern pat = pattern(p);
        const bool strict = pat == Pattern::kInvalid;
        if (strict) {  // resolve by exact sides for this piece, then back to the tolerance
          begin_plane(Plane(plane_), plane_id_, 0.0);
          pat = pattern(p);
        }
        switch (pat) {
          case Pattern::kBack: kept.push_back(p); break;
          case Pattern::kFront: break;
          case Pattern::kCrossing: {
            uint32_t g = split_face(p);
            pieces.push_back(g);
            kept.push_back(g);
            break;
          }
          case Pattern::kInvalid: kept.push_back(p); ++stats_.rejected_planes; break;
        }
        if (strict) begin_plane(Plane(plane_), plane_id_, 1.0);
      }
      inside = std::move(kept);
    }
    for (uint32_t p : inside) faces_[p].polygon = frag.polygon;
  }
}

// The canonical plane with normal ±h.normal (within 1e-6) passing within the snap
// tolerance of every point of `pts`; a new plane h when there is none. Planes are hashed by
// normal (cells of 1e-2 per component) and offset (cells of offset_cell_, which exceeds the
// offset difference of two such planes: ≤ |Δn| · max |p| + 2 snap, |Δn| ≤ 1.42e-3); a match
// lies in the normal cells around ±n (a neighbor only when n is within 1.5e-3 of its side)
// and the 3 offset cells around ±offset.
uint32_t Builder::plane_id(const Plane& h, const std::vector<dvec3>& pts) {
  const double snap = kSnapTolerance * model_.scale;
  auto key = [](int64_t x, int64_t y, int64_t z, int64_t w) {
    return (uint64_t(x) * 73856093u) ^ (uint64_t(y) * 19349663u) ^ (uint64_t(z) * 83492791u) ^ (uint64_t(w) * 2654435761u);
  };
  uint32_t found = kNone;
  for (double sign : {1.0, -1.0}) {
    const dvec3 n = sign * h.normal;
    int64_t k[3];
    int lo[3], hi[3];
    for (int i = 0; i < 3; ++i) {
      const double g = n[i] * 1e2;
      k[i] = std::llround(g);
      lo[i] = g - double(k[i]) < -0.5 + 0.15 ? -1 : 0;
      hi[i] = g - double(k[i]) > 0.5 - 0.15 ? 1 : 0;
    }
    const int64_t kw = std::llround(sign * h.offset / offset_cell_);
    for (int dx = lo[0]; dx <= hi[0]; ++dx)
      for (int dy = lo[1]; dy <= hi[1]; ++dy)
        for (int dz = lo[2]; dz <= hi[2]; ++dz)
          for (int dw = -1; dw <= 1; ++dw) {
            auto it = plane_buckets_.find(key(k[0] + dx, k[1] + dy, k[2] + dz, kw + dw));
            if (it == plane_buckets_.end()) continue;
            for (uint32_t id : it->second) {
              if (found != kNone && id >= found) continue;  // the earliest match: deterministic
              const Plane& q = planes_[id];
              if (std::abs(glm::dot(q.normal, h.normal)) < 1.0 - 1e-6) continue;
              bool on = true;
              for (const dvec3& v : pts) on &= std::abs(q.distance(v)) <= snap;
              if (on) found = id;
            }
          }
  }
  if (found == kNone) {
    found = uint32_t(planes_.size());
    planes_.push_back(h);
    plane_buckets_[key(std::llround(h.normal.x * 1e2), std::llround(h.normal.y * 1e2), std::llround(h.normal.z * 1e2),
                       std::llround(h.offset / offset_cell_))]
        .push_back(found);
  }
  return found;
}

// Candidate planes for a cell's fragments, best first: k evenly spaced fragments' planes
// plus the `largest` of largest area — big occluders (floor slabs, long walls) whose planes
// rarely split anything and keep distant parts of the model (other floors) from fragmenting
// each other's cells — scored split_weight · (fragments split) + |front − back|.
std::vector<uint32_t> Builder::rank_splitters(const std::vector<Fragment>& frags) {
  const size_t k = std::min<size_t>(size_t(std::max(1, options_.candidates)), frags.size());
  std::vector<uint32_t> candidates;
  for (size_t c = 0; c < k; ++c) candidates.push_back(poly_plane_[frags[c * frags.size() / k].polygon]);
  const size_t big = std::min<size_t>(size_t(std::max(0, options_.largest)), frags.size());
  if (big > 0) {
    std::vector<std::pair<double, uint32_t>> by_area;
    for (const Fragment& f : frags) by_area.push_back({-glm::length(newell_normal(f.v)), f.polygon});
    std::partial_sort(by_area.begin(), by_area.begin() + long(big), by_area.end());
    for (size_t c = 0; c < big; ++c) candidates.push_back(poly_plane_[by_area[c].second]);
  }
  std::vector<std::pair<double, uint32_t>> scored;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const uint32_t id = candidates[i];
    if (std::find(candidates.begin(), candidates.begin() + long(i), id) != candidates.begin() + long(i)) continue;
    const Plane& h = planes_[id];
    size_t front = 0, back = 0, split = 0;
    for (const Fragment& f : frags) {
      if (poly_plane_[f.polygon] == id) continue;
      bool plus = false, minus = false;
      for (const dvec3& p : f.v) {
        double d = h.distance(p);
        plus |= d > eps_;
        minus |= d < -eps_;
      }
      if (plus && minus) ++split;
      else if (plus) ++front;
      else if (minus) ++back;
    }
    scored.push_back({options_.split_weight * double(split) + std::abs(double(front) - double(back)), id});
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<uint32_t> out;
  for (const auto& [score, id] : scored) out.push_back(id);
  return out;
}

void Builder::make_box() {
  Bounds3 b;
  for (const InputPolygon& p : model_.polygons)
    for (const dvec3& v : p.vertices) b.extend(vec3(v));
  const dvec3 margin(options_.box_margin * model_.scale + 1e-9);
  const dvec3 lo = b.empty() ? dvec3(-1.0) : dvec3(b.min) - margin;
  const dvec3 hi = b.empty() ? dvec3(1.0) : dvec3(b.max) + margin;
  const uint32_t box = uint32_t(planes_.size());  // box face f has plane id box + f
  for (int i = 0; i < 8; ++i)
    add_vertex({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z},
               {box + ((i & 1) ? 1u : 0u), box + ((i & 2) ? 3u : 2u), box + ((i & 4) ? 5u : 4u)});
  // Corner bits (x, y, z); each face listed counter-clockwise seen from outside.
  const uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  const dvec3 normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  cells_.emplace_back();
  for (int f = 0; f < 6; ++f) {
    BuildFace face;
    face.loop.assign(quads[f], quads[f] + 4);
    face.plane.normal = normals[f];
    face.plane.offset = -glm::dot(normals[f], verts_[quads[f][0]]);
    face.plane_id = box + uint32_t(f);
    planes_.push_back(face.plane);  // box planes are never matched: nothing lies on them
    face.cell[0] = 0;  // inside the box is behind every outward face
    for (int k = 0; k < 4; ++k)
      edge_faces_[edge_key(quads[f][k], quads[f][(k + 1) % 4])].push_back(uint32_t(f));
    faces_.push_back(face);
    cells_[0].push_back(uint32_t(f));
  }
}

// Sutherland–Hodgman split of a convex fragment by a plane (vertices within eps on both).
void clip_fragment(const Fragment& f, const Plane& h, double eps, Fragment& front, Fragment& back) {
  const size_t n = f.v.size();
  for (size_t i = 0; i < n; ++i) {
    const dvec3& a = f.v[i];
    const dvec3& b = f.v[(i + 1) % n];
    double da = h.distance(a), db = h.distance(b);
    int sa = da > eps ? 1 : (da < -eps ? -1 : 0), sb = db > eps ? 1 : (db < -eps ? -1 : 0);
    if (sa >= 0) front.v.push_back(a);
    if (sa <= 0) back.v.push_back(a);
    if (sa * sb < 0) {
      dvec3 x = a + (b - a) * (da / (da - db));
      front.v.push_back(x);
      back.v.push_back(x);
    }
  }
  front.polygon = back.polygon = f.polygon;
}

WingedPair Builder::run() {
  Stopwatch watch;
  // Canonical planes of the input: a polygon whose vertices all lie within the snap
  // tolerance of an earlier polygon's plane (same or opposite normal) shares its id.
  double reach = 0.0;  // max |p| over the input and the outer box (within its margin)
  for (const InputPolygon& p : model_.polygons)
    for (const dvec3& v : p.vertices) reach = std::max(reach, glm::length(v));
  reach += (options_.box_margin + 1.0) * model_.scale;
  offset_cell_ = 1.5e-3 * reach + 4.0 * kSnapTolerance * model_.scale;
  for (const InputPolygon& p : model_.polygons) poly_plane_.push_back(plane_id(p.plane, p.vertices));
  make_box();
  std::vector<Fragment> all;
  // Each polygon starts projected onto its canonical plane (a move within the snap
  // tolerance), so every side decision about it agrees with the faces made on that plane.
  for (uint32_t p = 0; p < model_.polygons.size(); ++p) {
    const Plane& h = planes_[poly_plane_[p]];
    Fragment f{model_.polygons[p].vertices, p};
    for (dvec3& v : f.v) v -= h.normal * h.distance(v);
    all.push_back(std::move(f));
  }
  auto big_enough = [&](const Fragment& f) {
    return f.v.size() >= 3 && glm::length(newell_normal(f.v)) > 2.0 * eps_area_;
  };
  struct Item {
    uint32_t cell;
    std::vector<Fragment> frags;
    int aux;  // auxiliary splits above this cell (see below)
  };
  std::vector<Item> stack;
  stack.push_back({0, std::move(all), 0});
  while (!stack.empty()) {
    auto [c, frags, aux] = std::move(stack.back());
    stack.pop_back();
    if (frags.empty()) continue;
    // The best-ranked plane that cuts the cell consistently (by the tolerance, else by
    // exact sides); then any other plane of the cell's fragments; then an auxiliary plane
    // (through the cell's box center, across its longest side) that changes the cell
    // around the near-degenerate spot, and the children try again (≤ kMaxAux deep).
    // A fragment is never dropped while some plane can still be used.
    constexpr int kMaxAux = 12;
    std::vector<uint32_t> order = rank_splitters(frags);
    uint32_t id = kNone, aux_id = kNone;
    Cut cut;
    for (size_t i = 0; cut.face == kNone && !cut.boundary; ++i) {
      if (i == order.size()) {
        for (const Fragment& f : frags)
          if (std::find(order.begin(), order.end(), poly_plane_[f.polygon]) == order.end())
            order.push_back(poly_plane_[f.polygon]);
        if (i == order.size() && aux_id == kNone && aux < kMaxAux) {
          dvec3 lo(INFINITY), hi(-INFINITY);
          for (uint32_t f : cells_[c])
            for (uint32_t v : faces_[f].loop) {
              lo = glm::min(lo, verts_[v]);
              hi = glm::max(hi, verts_[v]);
            }
          const dvec3 ext = hi - lo, center = 0.5 * (lo + hi);
          const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
          Plane a;
          a.normal = dvec3(0.0);
          a.normal[axis] = 1.0;
          a.offset = -center[axis];
          aux_id = plane_id(a, {center});
          order.push_back(aux_id);
        }
        if (i == order.size()) break;
      }
      id = order[i];
      cut = cut_by(c, id, id != aux_id);
    }
    std::vector<Fragment> coplanar, front, back;
    // A boundary cut: the cell lies on one side of the plane, its fragments on the plane
    // lie on the cell's boundary (within eps) and are carved into the faces there.
    if (cut.boundary) {
      std::vector<Fragment> rest;
      for (Fragment& f : frags) (poly_plane_[f.polygon] == id ? coplanar : rest).push_back(std::move(f));
      std::vector<uint32_t>& on = cut.on;
      if (on.empty()) {
        // Beyond the tolerance from the plane's faces (a near-degenerate cell): the faces of
        // the cell parallel to the plane and nearest to it take the fragments, so they still
        // block sightlines (a conservative placement, counted), never a hole.
        double best = INFINITY;
        const Plane& h = planes_[id];
        for (uint32_t f : cells_[c]) {
          if (std::abs(glm::dot(faces_[f].plane.normal, h.normal)) < 1.0 - 1e-6) continue;
          double d = 0.0;
          for (uint32_t v : faces_[f].loop) d = std::max(d, std::abs(h.distance(verts_[v])));
          if (d < best - eps_) on.clear();
          if (d <= best + eps_) on.push_back(f);
          best = std::min(best, d);
        }
        (on.empty() ? stats_.unplaced_fragments : stats_.displaced_fragments) += coplanar.size();
      }
      for (uint32_t f : on) carve(f, coplanar);
      stack.push_back({c, std::move(rest), aux});
      continue;
    }
    if (cut.face == kNone) {
      seal(c, frags);
      continue;
    }
    // The fragments on the candidate plane lie on the separating face (moved onto it when
    // the plane was shifted: by at most kShifts' largest · eps).
    const Plane& h = planes_[cut.plane];
    for (Fragment& f : frags) {
      bool plus = false, minus = false;
      if (poly_plane_[f.polygon] == id && cut.plane != id)
        for (dvec3& v : f.v) v -= h.normal * h.distance(v);
      if (poly_plane_[f.polygon] != id)
        for (const dvec3& p : f.v) {
          double d = h.distance(p);
          plus |= d > eps_;
          minus |= d < -eps_;
        }
      if (!plus && !minus) coplanar.push_back(f);
      else if (!minus) front.push_back(f);
      else if (!plus) back.push_back(f);
      else {
        Fragment fp, bp;
        clip_fragment(f, h, eps_, fp, bp);
        ++stats_.fragments_split;
        if (big_enough(fp)) front.push_back(std::move(fp));
        if (big_enough(bp)) back.push_back(std::move(bp));
      }
    }
    ++stats_.splits;
    carve(cut.face, coplanar);
    const int next_aux = aux + (id == aux_id && aux_id != kNone ? 1 : 0);
    stats_.aux_splits += id == aux_id && aux_id != kNone;
    stack.push_back({cut.back, std::move(back), next_aux});
    stack.push_back({c, std::move(front), next_aux});
  }
  WingedPair wp = export_structure();
  stats_.build_ms = watch.elapsed_ms();
  return wp;
}

// The build structure → winged-pair records (pairs, clock, spin), compacted.
WingedPair Builder::export_structure() const {
  WingedPair wp;
  wp.scale = model_.scale;
  wp.polygon_count = uint32_t(model_.polygons.size());
  std::vector<uint32_t> vmap(verts_.size(), kNone);
  std::unordered_map<uint64_t, uint32_t> emap;
  for (uint32_t f = 0; f < faces_.size(); ++f) {
    const auto& loop = faces_[f].loop;
    const uint32_t base = uint32_t(wp.pairs.size()), n = uint32_t(loop.size());
    Face face;
    face.cell[0] = faces_[f].cell[0];
    face.cell[1] = faces_[f].cell[1];
    face.polygon = faces_[f].polygon;
    face.plane = faces_[f].plane;
    face.pair = base;
    wp.faces.push_back(face);
    for (uint32_t v : loop) {
      if (vmap[v] == kNone) {
        vmap[v] = uint32_t(wp.vertices.size());
        wp.vertices.push_back({verts_[v], kNone});
      }
    }
    for (uint32_t i = 0; i < n; ++i) {
      uint32_t a = vmap[loop[i]], b = vmap[loop[(i + 1) % n]];
      auto [it, fresh] = emap.try_emplace(edge_key(a, b), uint32_t(wp.edges.size()));
      if (fresh) {
        Edge e;
        e.vertex[0] = a;
        e.vertex[1] = b;
        e.pair = base + i;
        wp.edges.push_back(e);
        if (wp.vertices[a].edge == kNone) wp.vertices[a].edge = it->second;
        if (wp.vertices[b].edge == kNone) wp.vertices[b].edge = it->second;
      }
      Pair p;
      p.face = f;
      p.edge = it->second;
      p.direction = wp.edges[it->second].vertex[0] == a ? 1 : 0;
      p.clock[0] = base + (i + 1) % n;
      p.clock[1] = base + (i + n - 1) % n;
      wp.pairs.push_back(p);
    }
  }
  // The pairs of each edge (counting sort: one flat array), then spin: faces around each
  // edge sorted by angle about vertex[1] − vertex[0].
  std::vector<uint32_t> edge_first(wp.edges.size() + 1, 0), edge_pair(wp.pairs.size());
  for (const Pair& p : wp.pairs) ++edge_first[p.edge + 1];
  for (size_t e = 0; e < wp.edges.size(); ++e) edge_first[e + 1] += edge_first[e];
  {
    std::vector<uint32_t> fill(edge_first.begin(), edge_first.end() - 1);
    for (uint32_t p = 0; p < wp.pairs.size(); ++p) edge_pair[fill[wp.pairs[p].edge]++] = p;
  }
  std::vector<std::pair<double, uint32_t>> order;
  for (uint32_t e = 0; e < wp.edges.size(); ++e) {
    const std::span<const uint32_t> list(edge_pair.data() + edge_first[e], edge_first[e + 1] - edge_first[e]);
    const dvec3 p0 = wp.vertices[wp.edges[e].vertex[0]].position;
    const dvec3 u = glm::normalize(wp.vertices[wp.edges[e].vertex[1]].position - p0);
    const dvec3 x = glm::normalize(std::abs(u.x) < 0.9 ? glm::cross(u, dvec3(1, 0, 0))
                                                       : glm::cross(u, dvec3(0, 1, 0)));
    const dvec3 y = glm::cross(u, x);
    order.clear();
    for (uint32_t p : list) {
      const Pair& pr = wp.pairs[p];
      // Into the face: left of the counter-clockwise walk, seen from the front.
      dvec3 into = glm::cross(wp.faces[pr.face].plane.normal, pr.direction ? u : -u);
      order.push_back({std::atan2(glm::dot(into, y), glm::dot(into, x)), p});
    }
    std::sort(order.begin(), order.end());
    for (size_t i = 0; i < order.size(); ++i) {
      wp.pairs[order[i].second].spin[0] = order[(i + 1) % order.size()].second;
      wp.pairs[order[i].second].spin[1] = order[(i + order.size() - 1) % order.size()].second;
    }
  }
  for (uint32_t c = 0; c < cells_.size(); ++c) {
    Cell cell;
    cell.face = cells_[c].empty() ? kNone : cells_[c].front();
    wp.cells.push_back(cell);
  }
  finalize(wp);
  return wp;
}

}  // namespace

WingedPair build_winged_pair(const ModelPolygons& model, const BspOptions& options, BspStats* stats) {
  BspStats local;
  BspStats& s = stats ? *stats : local;
  s = BspStats{};
  s.polygons = model.polygons.size();
  Builder builder(model, options, s);
  return builder.run();
}

}  // namespace proxima::visibility
