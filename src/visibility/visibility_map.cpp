// Beam tracing of Funkhouser, "A visibility algorithm for hybrid geometry- and image-based
// modeling and rendering", section 4 (Figure 6: TraceBeams). Symbols: V = camera eye, C =
// current cell, B = current beam = the pyramid from V through the current convex region R
// of the visibility map M; F_i = boundary faces of C seen from inside (V on C's side of
// their plane). R_i = R ∩ projection(F_i); a transparent F_i recurses into the neighbor
// cell C_i with R_i (the trimmed beam B_i), an opaque F_i ends a final region of M.
// Regions carry, per boundary edge, the winged-pair edge it lies on, so the planar map's
// edges, adjacency and silhouettes (orientation of the opaque faces around the edge,
// found by spin references) come out of the traversal.
#include "proxima/visibility/visibility_map.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <unordered_map>

#include "proxima/core/error.h"
#include "proxima/core/timer.h"

namespace proxima::visibility {
namespace {

struct LVert {
  dvec2 p;
  uint32_t label;  // source of the edge from this vertex to the next
};
using LPoly = std::vector<LVert>;

double cross2(const dvec2& a, const dvec2& b) { return a.x * b.y - a.y * b.x; }

double shoelace(const LPoly& poly) {
  double a = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) a += cross2(poly[i].p, poly[(i + 1) % poly.size()].p);
  return 0.5 * a;
}

// Removes vertices closer than `tol` pixels to their successor (the edge that follows the
// removed vertex keeps its label) and reflex vertices: a vertex where the boundary turns
// against the polygon's orientation by more than 1e-9 rad with a dent of at most 1e-6 px²,
// and the tips of spikes (a turn of ~180°: the polygon runs out along a line and back). The polygon is convex in
// exact arithmetic; rounding in a clip near a vertex leaves near-zero edges with arbitrary
// directions and dents, and each of their supporting lines, used to clip a later beam,
// cuts away a wedge of it (holes in the map). Removing a reflex vertex fills its dent
// (the triangle it makes with its neighbors, of rounding size): the merged edge keeps the
// longer edge's label. `max_dent` caps the dent a removed reflex vertex may leave; a face's
// projection passes no cap (see project_face).
void drop_tiny_edges(LPoly& poly, double tol = 1e-6, double max_dent = 2e-6) {
  const double tol2 = tol * tol;
  size_t i = 0;
  while (poly.size() >= 3 && i < poly.size()) {
    const size_t j = (i + 1) % poly.size();
    const dvec2 d = poly[j].p - poly[i].p;
    if (glm::dot(d, d) < tol2) {
      poly[i].label = poly[j].label;
      poly.erase(poly.begin() + long(j));
      if (j < i) --i;
    } else {
      ++i;
    }
  }
  const double orient = shoelace(poly) < 0.0 ? -1.0 : 1.0;
  for (bool changed = true; changed && poly.size() >= 3;) {
    changed = false;
    for (size_t k = 0; k < poly.size() && poly.size() >= 3; ++k) {
      const size_t n = poly.size(), prev = (k + n - 1) % n;
      const dvec2 a = poly[k].p - poly[prev].p, b = poly[(k + 1) % n].p - poly[k].p;
      const double la = glm::length(a), lb = glm::length(b), turn = orient * cross2(a, b);
      const bool spike = glm::dot(a, b) < 0.0 && std::abs(turn) <= 1e-9 * la * lb;
      if (spike || (turn < -1e-9 * la * lb && turn > -max_dent)) {
        if (!spike && lb > la) poly[prev].label = poly[k].label;
        poly.erase(poly.begin() + long(k));
        changed = true;
        break;
      }
    }
  }
}

// Keeps the part of `poly` left of the directed line a → b in `out`; new edges along the
// line get `label`. Returns false, leaving `out` untouched, when no vertex of `poly` lies
// right of the line: the polygon is kept whole (it is already free of tiny edges).
bool clip_left(const LPoly& poly, const dvec2& a, const dvec2& b, uint32_t label, LPoly& out) {
  const size_t n = poly.size();
  const dvec2 d = b - a;
  const double tol = 1e-12 * std::max(1.0, glm::dot(d, d));
  bool any_out = false;
  for (size_t i = 0; i < n && !any_out; ++i) any_out = cross2(d, poly[i].p - a) < -tol;
  if (!any_out) return false;
  out.clear();
  for (size_t i = 0; i < n; ++i) {
    const LVert& cur = poly[i];
    const LVert& nxt = poly[(i + 1) % n];
    double sc = cross2(d, cur.p - a), sn = cross2(d, nxt.p - a);
    bool cin = sc >= -tol, nin = sn >= -tol;
    if (cin) out.push_back(cur);
    if (cin != nin) {
      dvec2 x = cur.p + (nxt.p - cur.p) * (sc / (sc - sn));
      out.push_back({x, cin ? label : cur.label});
    }
  }
  drop_tiny_edges(out);
  return true;
}

struct Box2 {
  dvec2 lo{INFINITY}, hi{-INFINITY};
};

Box2 box_of(const LPoly& poly) {
  Box2 b;
  for (const LVert& v : poly) {
    b.lo = glm::min(b.lo, v.p);
    b.hi = glm::max(b.hi, v.p);
  }
  return b;
}

// When the union of the convex polygons a and b (disjoint interiors, areas summing to
// `area`) is convex — their convex hull has that area within 1e-9 relative + 1e-7 px² —
// writes it to `out` (counter-clockwise, each edge labeled with the edge of a or b it runs
// along) and returns true.
bool convex_union(const LPoly& a, const LPoly& b, double area, LPoly& out) {
  std::vector<dvec2> pts;
  for (const LVert& v : a) pts.push_back(v.p);
  for (const LVert& v : b) pts.push_back(v.p);
  std::sort(pts.begin(), pts.end(), [](const dvec2& x, const dvec2& y) { return x.x < y.x || (x.x == y.x && x.y < y.y); });
  std::vector<dvec2> h(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {  // Andrew's monotone chain, collinear points dropped
    while (k >= 2 && cross2(h[k - 1] - h[k - 2], pts[i] - h[k - 2]) <= 0.0) --k;
    h[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(h[k - 1] - h[k - 2], pts[i] - h[k - 2]) <= 0.0) --k;
    h[k++] = pts[i];
  }
  h.resize(k > 0 ? k - 1 : 0);
  if (h.size() < 3) return false;
  double hull_area = 0.0;
  for (size_t i = 0; i < h.size(); ++i) hull_area += cross2(h[i], h[(i + 1) % h.size()]);
  hull_area *= 0.5;
  if (std::abs(hull_area - area) > 1e-9 * area + 1e-7) return false;
  out.clear();
  for (size_t i = 0; i < h.size(); ++i) {
    const dvec2 p = h[i], d = h[(i + 1) % h.size()] - p;
    uint32_t label = kNone, fallback = kNone;
    for (const LPoly* poly : {&a, &b})
      for (size_t j = 0; j < poly->size() && label == kNone; ++j) {
        if ((*poly)[j].p != p) continue;
        const dvec2 e = (*poly)[(j + 1) % poly->size()].p - p;
        if (fallback == kNone) fallback = (*poly)[j].label;
        if (glm::dot(d, e) > 0.0 && std::abs(cross2(d, e)) <= 1e-9 * glm::length(d) * glm::length(e))
          label = (*poly)[j].label;
      }
    out.push_back({p, label != kNone ? label : fallback});
  }
  // Hull vertices a rounding error apart (a vertex of a and one of b meant to be one) leave
  // a near-zero edge whose direction is arbitrary: cleaned as after every clip.
  drop_tiny_edges(out);
  return out.size() >= 3;
}

// A face of the current cell seen from inside: its projection (made on first use) and the
// pieces of it the incoming beams cover.
struct SeenFace {
  uint32_t face;
  LPoly q;
  Box2 box;
  bool projected;
  std::vector<LPoly> pieces;
  double area;  // sum of the pieces' areas
};

struct Camera64 {
  dvec3 eye, right, up, forward;
  double f, cx, cy;
};

class Tracer {
 public:
  Tracer(const WingedPair& wp, const Camera& cam, const TraceOptions& options)
      : wp_(wp), culling_(options.beam_culling), rejoin_(options.rejoin), escape_(options.escape) {
    c_.eye = dvec3(cam.position);
    c_.right = dvec3(camera_right(cam));
    c_.up = dvec3(camera_up(cam));
    c_.forward = dvec3(camera_forward(cam));
    c_.f = double(focal_length_px(cam));
    c_.cx = 0.5 * cam.width;
    c_.cy = 0.5 * cam.height;
    zmin_ = 1e-6 * wp.scale;
    eye_tol_ = 1e-9 * wp.scale;
  }

  // Whether face f is seen from inside cell c (the eye strictly on c's side of its plane);
  // a face through the eye is seen edge-on from both sides and skipped.
  bool seen_from_inside(uint32_t f, uint32_t c) const {
    const Face& face = wp_.faces[f];
    const double d = face.plane.distance(c_.eye);
    return face.cell[1] == c ? d > eye_tol_ : d < -eye_tol_;
  }

  // Starts from every cell holding the eye: an eye on a face (edge, vertex) of the BSP
  // sees each cell's half-space through that cell only, since the faces through the eye
  // are seen edge-on and skipped. Cells are processed front to back (a topological order
  // of "seen through": a cell is taken once every neighbor that can pass beams into it is
  // done; BSP cells admit one from any eye), so a cell sees all its incoming beams at
  // once. Beams are split by every transparent face they cross, but where the beams
  // entering a cell together cover a face's whole projection, the face passes on one beam,
  // its projection, instead of the pieces: fragments rejoin in free space and the beam
  // count follows the visible structure, not the paths through the cells.
  void trace(const std::vector<uint32_t>& start, const LPoly& frame, VisibilityMap& map) {
    const size_t nc = wp_.cells.size();
    std::vector<uint32_t> entries(nc, 0);  // faces a beam can still enter each cell through
    for (uint32_t f = 0; f < wp_.faces.size(); ++f) {
      const Face& face = wp_.faces[f];
      if (face.cell[0] == kNone || face.cell[1] == kNone) continue;
      for (int k = 0; k < 2; ++k)
        if (seen_from_inside(f, face.cell[k])) ++entries[face.cell[1 - k]];
    }
    inbox_.assign(nc, {});
    for (uint32_t c : start) inbox_[c].push_back(frame);
    std::vector<uint32_t> ready;
    for (uint32_t c = uint32_t(nc); c-- > 0;)
      if (entries[c] == 0) ready.push_back(c);
    while (!ready.empty()) {
      const uint32_t c = ready.back();
      ready.pop_back();
      if (!inbox_[c].empty()) trace_cell(c, frame, map);
      for (uint32_t f : wp_.faces_of_cell(c)) {
        const uint32_t next = wp_.cell_across(f, c);
        if (next != kNone && seen_from_inside(f, c) && --entries[next] == 0) ready.push_back(next);
      }
    }
    // Beams left waiting: a cycle of cells each in front of the other (a corrupt --load file).
    for (const std::vector<LPoly>& in : inbox_)
      if (!in.empty())
        fail_input("inconsistent winged pair: cells that lie in front of each other (overlapping cells)");
  }

  // Splits the beams entering cell c among the faces it sees from inside.
  void trace_cell(uint32_t c, const LPoly& frame, VisibilityMap& map) {
    ++map.stats.cells_visited;
    std::vector<LPoly> in = std::move(inbox_[c]);
    inbox_[c] = {};
    if (rejoin_ && in.size() > 1) merge_pieces(in);
    seen_.clear();
    for (uint32_t f : wp_.faces_of_cell(c))
      if (seen_from_inside(f, c)) seen_.push_back({f, {}, {}, false, {}, 0.0});
    LPoly r, tmp;
    for (const LPoly& region : in) {
      // Faces whose projection's bounding box misses the region's by more than the clip
      // tolerance would clip to nothing: skip them before clipping (same result, cheaper).
      Box2 rb = box_of(region);
      rb.lo -= dvec2(1e-6);
      rb.hi += dvec2(1e-6);
      if (culling_) beam_planes(region);
      for (SeenFace& s : seen_) {
        if (culling_ && outside_beam(s.face)) {
          ++map.stats.faces_culled;
          continue;
        }
        if (!s.projected) {
          project_face(s.face, s.q);
          s.box = box_of(s.q);
          s.projected = true;
        }
        if (s.q.size() < 3) continue;
        if (s.box.lo.x > rb.hi.x || s.box.lo.y > rb.hi.y || s.box.hi.x < rb.lo.x || s.box.hi.y < rb.lo.y) continue;
        r = s.q;
        for (size_t k = 0; k < region.size() && r.size() >= 3; ++k)
          if (clip_left(r, region[k].p, region[(k + 1) % region.size()].p, region[k].label, tmp)) r.swap(tmp);
        if (r.size() < 3) continue;
        const double area = shoelace(r);
        if (area <= 1e-9) continue;
        ++map.stats.beams;
        s.area += area;
        s.pieces.push_back(r);
      }
    }
    for (SeenFace& s : seen_) {
      if (s.pieces.empty()) continue;
      if (rejoin_ && s.pieces.size() > 1) rejoin(s, frame);
      if (rejoin_ && s.pieces.size() > 1) merge_pieces(s.pieces);
      const Face& face = wp_.faces[s.face];
      const uint32_t next = wp_.cell_across(s.face, c);
      if (!face.opaque() && next != kNone) {
        if (!escape_ || !escapes(s.face)) {
          for (LPoly& p : s.pieces) inbox_[next].push_back(std::move(p));
          continue;
        }
        ++map.stats.escaped;
      }
      for (const LPoly& p : s.pieces) {
        MapRegion region;
        region.face = s.face;
        region.polygon = face.polygon;
        for (const LVert& v : p) {
          region.vertices.push_back(v.p);
          region.edge_source.push_back(v.label);
        }
        map.regions.push_back(std::move(region));
      }
    }
  }

  // Merges pieces of one face pairwise while the union of two is convex (the convex hull
  // of both has their summed area within 1e-9 relative + 1e-7 px²): the pieces of a face
  // partly hidden are split by the free-space faces their beams crossed, most of which do
  // not bound what is visible.
  void merge_pieces(std::vector<LPoly>& pieces) {
    std::vector<Box2> boxes;
    std::vector<double> areas;
    for (const LPoly& p : pieces) {
      boxes.push_back(box_of(p));
      areas.push_back(shoelace(p));
    }
    LPoly hull;
    for (size_t i = 0; i < pieces.size(); ++i) {
      for (size_t j = i + 1; j < pieces.size();) {
        const Box2& a = boxes[i];
        const Box2& b = boxes[j];
        const double t = 1e-6;
        if (a.lo.x > b.hi.x + t || b.lo.x > a.hi.x + t || a.lo.y > b.hi.y + t || b.lo.y > a.hi.y + t ||
            !convex_union(pieces[i], pieces[j], areas[i] + areas[j], hull)) {
          ++j;
          continue;
        }
        pieces[i].swap(hull);
        boxes[i] = box_of(pieces[i]);
        areas[i] += areas[j];
        pieces[j].swap(pieces.back());
        boxes[j] = boxes.back();
        areas[j] = areas.back();
        pieces.pop_back();
        boxes.pop_back();
        areas.pop_back();
        j = i + 1;  // the grown piece may now join earlier candidates
      }
    }
  }

  // When the pieces of a face's projection (disjoint beams) cover all of it inside the
  // frame — their areas sum to its area within 1e-9 relative + 1e-7 px² — they are replaced
  // by that one polygon: every sightline through the face passed through the cell.
  void rejoin(SeenFace& s, const LPoly& frame) {
    LPoly whole = s.q, tmp;
    for (size_t k = 0; k < frame.size() && whole.size() >= 3; ++k)
      if (clip_left(whole, frame[k].p, frame[(k + 1) % frame.size()].p, kImageBorder, tmp)) whole.swap(tmp);
    if (whole.size() < 3) return;
    const double area = shoelace(whole);
    if (std::abs(area - s.area) > 1e-9 * area + 1e-7) return;
    s.pieces.assign(1, std::move(whole));
  }

  // The planes through the eye and the region's edges, world space, unit normals pointing
  // into the beam. Pixel p(x, y, z) = (cx + f·x/z, cy − f·y/z) lies left of a → b (d = b − a)
  // iff z · cross2(d, p − a) ≥ 0, a linear form in camera space (x, y, z).
  void beam_planes(const LPoly& region) {
    planes_.clear();
    for (size_t k = 0; k < region.size(); ++k) {
      const dvec2 a = region[k].p, d = region[(k + 1) % region.size()].p - a;
      const dvec3 n = -d.y * c_.f * c_.right - d.x * c_.f * c_.up +
                      (d.x * (c_.cy - a.y) - d.y * (c_.cx - a.x)) * c_.forward;
      const double len = glm::length(n);
      if (len > 0.0) planes_.push_back(n / len);
    }
  }

  // True when every vertex of face f lies outside one beam plane by more than 1e-7 · scale:
  // the face (convex) misses the beam and would clip to nothing.
  bool outside_beam(uint32_t f) const {
    const double margin = 1e-7 * wp_.scale;
    auto verts = wp_.face_vertices(f);
    for (const dvec3& n : planes_) {
      bool all_out = true;
      for (uint32_t v : verts)
        if (glm::dot(n, wp_.vertices[v].position - c_.eye) >= -margin) {
          all_out = false;
          break;
        }
      if (all_out) return true;
    }
    return false;
  }

  // True when every sightline through face f has left the opaque faces' bounding box for
  // good: all of f's vertices lie on or beyond one side of the box, farther out than the
  // eye. Past f (a transparent face: no opaque face shares its points) such a sightline
  // lies strictly beyond that side, so it meets no opaque face: the beam
  // ends there as background instead of being split by the free-space cells it still
  // crosses (outside a building, every extended wall plane cuts them).
  bool escapes(uint32_t f) const {
    auto verts = wp_.face_vertices(f);
    for (int axis = 0; axis < 3; ++axis) {
      bool above = true, below = true;
      for (uint32_t v : verts) {
        const double x = wp_.vertices[v].position[axis];
        above &= x >= wp_.opaque_hi[axis] && x > c_.eye[axis];
        below &= x <= wp_.opaque_lo[axis] && x < c_.eye[axis];
      }
      if (above || below) return true;
    }
    return false;
  }

  // The face clipped to depth ≥ zmin, projected to pixels, counter-clockwise (positive
  // shoelace area), into `out`; edges labeled with their winged-pair edges.
  void project_face(uint32_t f, LPoly& out) {
    out.clear();
    auto verts = wp_.face_vertices(f);
    auto edges = wp_.face_edges(f);
    const size_t n = verts.size();
    auto& cam = cam_;  // (camera-space right/up/depth, label)
    cam.clear();
    for (size_t i = 0; i < n; ++i) {
      dvec3 d = wp_.vertices[verts[i]].position - c_.eye;
      cam.push_back({{glm::dot(d, c_.right), glm::dot(d, c_.up), glm::dot(d, c_.forward)}, edges[i]});
    }
    // Clip to depth ≥ zmin, then to the frame grown by a 1-pixel guard band (pixel u ≥ −g
    // ⇔ f·x + (cx + g)·z ≥ 0, etc.), so projected coordinates stay near the image: a face
    // grazing the eye would otherwise project to ~1e7 px and lose the precision the
    // region clipping needs. New edges lie outside the frame (kImageBorder).
    const double g = 1.0, w = 2.0 * c_.cx, h = 2.0 * c_.cy;
    const glm::dvec4 bounds[5] = {{0.0, 0.0, 1.0, -zmin_},
                             {c_.f, 0.0, c_.cx + g, 0.0},
                             {-c_.f, 0.0, w + g - c_.cx, 0.0},
                             {0.0, -c_.f, c_.cy + g, 0.0},
                             {0.0, c_.f, h + g - c_.cy, 0.0}};
    auto& clipped = clipped_;
    for (const glm::dvec4& k : bounds) {
      clipped.clear();
      const size_t m = cam.size();
      for (size_t i = 0; i < m; ++i) {
        const auto& [a, la] = cam[i];
        const auto& [b, lb] = cam[(i + 1) % m];
        const double sa = glm::dot(dvec3(k), a) + k.w, sb = glm::dot(dvec3(k), b) + k.w;
        const bool ain = sa >= 0.0, bin = sb >= 0.0;
        if (ain) clipped.push_back({a, la});
        if (ain != bin) clipped.push_back({a + (b - a) * (sa / (sa - sb)), ain ? kImageBorder : la});
      }
      cam.swap(clipped);
      if (cam.size() < 3) return;
    }
    for (const auto& [p, l] : cam) out.push_back({{c_.cx + c_.f * p.x / p.z, c_.cy - c_.f * p.y / p.z}, l});
    // Every reflex vertex goes, whatever its dent: a BSP face is convex only up to the
    // plane tolerance (a vertex classified on a plane within it lies up to that far off
    // the face's straight edge), and its projection, passed on as a beam, clips the next
    // cell's faces by each edge's line, so a reflex vertex there cuts a wedge out of them
    // (lost area, a hole). Filling the dent covers sightlines of the neighbor face as well:
    // an overlap of the tolerance's size, never a hole.
    drop_tiny_edges(out, 1e-6, INFINITY);
    if (out.size() >= 3 && shoelace(out) < 0.0) {
      LPoly rev;
      const size_t m = out.size();
      for (size_t k = 0; k < m; ++k) rev.push_back({out[m - 1 - k].p, out[(2 * m - 2 - k) % m].label});
      out = std::move(rev);
    }
  }

  // Occluding contour test for winged-pair edge e (spin around it).
  bool silhouette(uint32_t e) {
    auto [it, fresh] = silhouette_cache_.try_emplace(e, false);
    if (!fresh) return it->second;
    const Edge& edge = wp_.edges[e];
    const dvec3 p0 = wp_.vertices[edge.vertex[0]].position, p1 = wp_.vertices[edge.vertex[1]].position;
    const dvec3 m = glm::cross(p1 - c_.eye, p0 - c_.eye);
    const dvec3 u = p1 - p0;
    int plus = 0, minus = 0;
    uint32_t p = edge.pair;
    do {
      const Pair& pr = wp_.pairs[p];
      if (wp_.faces[pr.face].opaque()) {
        dvec3 into = glm::cross(wp_.faces[pr.face].plane.normal, pr.direction ? u : -u);
        double s = glm::dot(into, m);
        plus += s > 0.0;
        minus += s < 0.0;
      }
      p = pr.spin[0];
    } while (p != edge.pair);
    it->second = (plus > 0) != (minus > 0);
    return it->second;
  }

 private:
  const WingedPair& wp_;
  bool culling_, rejoin_, escape_;
  std::vector<dvec3> planes_;  // beam planes of the current region (beam_planes)
  Camera64 c_;
  double zmin_, eye_tol_;
  std::vector<std::pair<dvec3, uint32_t>> cam_, clipped_;  // project_face scratch
  std::vector<std::vector<LPoly>> inbox_;  // beams waiting to enter each cell
  std::vector<SeenFace> seen_;             // trace_cell scratch
  std::unordered_map<uint32_t, bool> silhouette_cache_;
};

// Hash buckets of dense ids (0, 1, 2, … in insertion order): each bucket a linked list in
// insertion order (first/last id in the map, `next_` per id) — no allocation per bucket.
class BucketLists {
 public:
  // The first id in bucket `key` for which match(id) holds, or kNone.
  template <class Match>
  uint32_t find(uint64_t key, Match&& match) const {
    auto it = heads_.find(key);
    if (it == heads_.end()) return kNone;
    for (uint32_t v = it->second.first; v != kNone; v = next_[v])
      if (match(v)) return v;
    return kNone;
  }
  // Appends the next id (= number of ids added so far) to bucket `key`.
  void add(uint64_t key) {
    const uint32_t v = uint32_t(next_.size());
    next_.push_back(kNone);
    auto [it, fresh] = heads_.try_emplace(key, v, v);
    if (!fresh) {
      next_[it->second.second] = v;
      it->second.second = v;
    }
  }
  static uint64_t key(int64_t x, int64_t y) { return (uint64_t(x) << 32) ^ uint64_t(uint32_t(y)); }

 private:
  std::vector<uint32_t> next_;
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> heads_;  // first, last id
};

// Vertex welding on the image plane (tolerance 1e-4 px) with a hash grid of 1/1024-px cells:
// a match lies in the point's cell or, only when the point is within 1e-4 px of a cell side,
// in the neighbor across it (other neighbors are skipped: same answer, ~1 lookup a point).
class Welder {
 public:
  explicit Welder(std::vector<dvec2>& out) : out_(out) {}
  uint32_t id(const dvec2& p) {
    const double gx = p.x * 1024.0, gy = p.y * 1024.0;
    const int64_t kx = std::llround(gx), ky = std::llround(gy);
    const double reach = 1e-4 * 1024.0, fx = gx - double(kx), fy = gy - double(ky);
    for (int64_t dx = -1; dx <= 1; ++dx) {
      if ((dx < 0 && fx - reach > -0.5) || (dx > 0 && fx + reach < 0.5)) continue;
      for (int64_t dy = -1; dy <= 1; ++dy) {
        if ((dy < 0 && fy - reach > -0.5) || (dy > 0 && fy + reach < 0.5)) continue;
        const uint32_t v = grid_.find(BucketLists::key(kx + dx, ky + dy),
                                      [&](uint32_t w) { return glm::length(out_[w] - p) < 1e-4; });
        if (v != kNone) return v;
      }
    }
    out_.push_back(p);
    grid_.add(BucketLists::key(kx, ky));
    return uint32_t(out_.size() - 1);
  }

 private:
  std::vector<dvec2>& out_;
  BucketLists grid_;
};

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// Planar map from the regions: segments grouped by source, cut at every vertex on the
// same source line into elementary edges with their left and right regions.
// Ids of supporting lines on the image plane: segments within 1e-5 px of one line share an
// id, so a boundary's two sides meet even when they lie on different (collinear) winged-pair
// edges — a polygon edge split by the BSP on one side, a face edge of the beam on the other.
class LineIndex {
 public:
  uint32_t id(const dvec2& a, const dvec2& b) {
    dvec2 d = glm::normalize(b - a);
    if (d.x < 0.0 || (d.x == 0.0 && d.y < 0.0)) d = -d;
    const double theta = std::atan2(d.y, d.x), rho = cross2(d, a);
    const int64_t kt = std::llround(theta * 1e5), kr = std::llround(rho * 1e3);
    for (int64_t dt = -1; dt <= 1; ++dt)
      for (int64_t dr = -1; dr <= 1; ++dr) {
        const uint32_t l = buckets_.find(BucketLists::key(kt + dt, kr + dr), [&](uint32_t k) {
          const Line& line = lines_[k];
          return std::abs(cross2(line.d, a - line.p)) < 1e-5 && std::abs(cross2(line.d, b - line.p)) < 1e-5;
        });
        if (l != kNone) return l;
      }
    lines_.push_back({a, d});
    buckets_.add(BucketLists::key(kt, kr));
    return uint32_t(lines_.size() - 1);
  }

 private:
  struct Line {
    dvec2 p, d;
  };
  std::vector<Line> lines_;
  BucketLists buckets_;
};

// Planar map from the regions: segments grouped by supporting line, cut at every vertex on
// the line into elementary edges with their left and right regions.
void build_planar_map(VisibilityMap& map, Tracer& tracer) {
  Welder welder(map.vertices);
  LineIndex lines;
  struct Seg {
    uint64_t group;
    uint32_t a, b, region, source;
  };
  std::vector<Seg> all;  // sorted by group below (one flat array: no allocation per line)
  std::vector<uint32_t> ids;
  for (uint32_t r = 0; r < map.regions.size(); ++r) {
    const MapRegion& reg = map.regions[r];
    const size_t n = reg.vertices.size();
    ids.clear();
    for (const dvec2& v : reg.vertices) ids.push_back(welder.id(v));
    for (size_t i = 0; i < n; ++i) {
      const uint32_t a = ids[i], b = ids[(i + 1) % n];
      if (a == b) continue;
      uint64_t group;
      if (reg.edge_source[i] == kImageBorder) {
        // One group per image side.
        const dvec2 mid = 0.5 * (reg.vertices[i] + reg.vertices[(i + 1) % n]);
        group = (uint64_t(1) << 32) | uint64_t(mid.y < 0.5 ? 0 : mid.y > map.height - 0.5 ? 1 : mid.x < 0.5 ? 2 : 3);
      } else {
        group = lines.id(reg.vertices[i], reg.vertices[(i + 1) % n]);
      }
      all.push_back({group, a, b, r, reg.edge_source[i]});
    }
  }
  std::stable_sort(all.begin(), all.end(), [](const Seg& x, const Seg& y) { return x.group < y.group; });
  std::vector<std::pair<double, uint32_t>> stops;
  std::vector<uint32_t> left, right, lsrc, rsrc;
  for (size_t g0 = 0, g1 = 0; g0 < all.size(); g0 = g1) {
    while (g1 < all.size() && all[g1].group == all[g0].group) ++g1;
    const std::span<const Seg> segs(all.data() + g0, g1 - g0);
    const uint64_t group = all[g0].group;
    const dvec2 o = map.vertices[segs.front().a];
    const dvec2 dir = glm::normalize(map.vertices[segs.front().b] - o);
    auto t_of = [&](uint32_t v) { return glm::dot(map.vertices[v] - o, dir); };
    stops.clear();
    for (const Seg& s : segs) {
      stops.push_back({t_of(s.a), s.a});
      stops.push_back({t_of(s.b), s.b});
    }
    std::sort(stops.begin(), stops.end());
    stops.erase(std::unique(stops.begin(), stops.end(),
                            [](const auto& x, const auto& y) { return x.second == y.second; }),
                stops.end());
    left.assign(stops.size(), kNone);
    right.assign(stops.size(), kNone);
    lsrc.assign(stops.size(), kNone);
    rsrc.assign(stops.size(), kNone);
    for (const Seg& s : segs) {
      double ta = t_of(s.a), tb = t_of(s.b);
      bool forward = tb > ta;
      double lo = std::min(ta, tb), hi = std::max(ta, tb);
      // Stops are sorted by t: start at the first one at or after lo.
      size_t k0 = size_t(std::lower_bound(stops.begin(), stops.end(), std::pair<double, uint32_t>{lo, 0}) - stops.begin());
      k0 = k0 > 0 ? k0 - 1 : 0;
      for (size_t k = k0; k + 1 < stops.size(); ++k) {
        double mid = 0.5 * (stops[k].first + stops[k + 1].first);
        if (mid >= hi) break;
        if (mid <= lo) continue;
        (forward ? left : right)[k] = s.region;
        (forward ? lsrc : rsrc)[k] = s.source;
      }
    }
    const bool border = group >> 32 == 1;
    for (size_t k = 0; k + 1 < stops.size(); ++k) {
      if (left[k] == kNone && right[k] == kNone) continue;
      MapEdge e;
      e.vertex[0] = stops[k].second;
      e.vertex[1] = stops[k + 1].second;
      e.region[0] = left[k];
      e.region[1] = right[k];
      e.source = border ? kImageBorder : (lsrc[k] != kNone ? lsrc[k] : rsrc[k]);
      const uint32_t pl = left[k] == kNone ? kNone : map.regions[left[k]].polygon;
      const uint32_t pr = right[k] == kNone ? kNone : map.regions[right[k]].polygon;
      // Either side's edge may be the occluding one (the other a collinear BSP edge).
      e.silhouette = !border && left[k] != kNone && right[k] != kNone && pl != pr &&
                     (tracer.silhouette(lsrc[k]) || (rsrc[k] != lsrc[k] && tracer.silhouette(rsrc[k])));
      map.stats.silhouette_edges += e.silhouette;
      map.edges.push_back(e);
    }
  }
  // Merge contiguous regions of one polygon.
  std::vector<uint32_t> parent(map.regions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  for (const MapEdge& e : map.edges) {
    if (e.region[0] == kNone || e.region[1] == kNone) continue;
    if (map.regions[e.region[0]].polygon != map.regions[e.region[1]].polygon) continue;
    parent[find_root(parent, e.region[0])] = find_root(parent, e.region[1]);
  }
  std::unordered_map<uint32_t, uint32_t> merged_id;
  std::vector<uint32_t> polys;
  for (uint32_t r = 0; r < map.regions.size(); ++r) {
    auto [it, fresh] = merged_id.try_emplace(find_root(parent, r), uint32_t(merged_id.size()));
    map.regions[r].merged = it->second;
    if (map.regions[r].polygon != kNone) polys.push_back(map.regions[r].polygon);
  }
  std::sort(polys.begin(), polys.end());
  map.stats.regions = map.regions.size();
  map.stats.merged_regions = merged_id.size();
  map.stats.visible_polygons = size_t(std::unique(polys.begin(), polys.end()) - polys.begin());
}

}  // namespace

VisibilityMap trace_visibility_map(const WingedPair& wp, const Camera& camera, const TraceOptions& options) {
  Stopwatch watch;
  validate_camera(camera, "camera");
  VisibilityMap map;
  map.width = camera.width;
  map.height = camera.height;
  const std::vector<uint32_t> start = locate_cells(wp, dvec3(camera.position));
  if (start.empty()) fail_input("camera at (" + std::to_string(camera.position.x) + ", " +
                                 std::to_string(camera.position.y) + ", " + std::to_string(camera.position.z) +
                                 ") is outside the winged pair's outer box");
  const double w = camera.width, h = camera.height;
  // The frame, counter-clockwise in pixel coordinates (x right, y down): positive shoelace.
  LPoly frame = {{{0, 0}, kImageBorder}, {{w, 0}, kImageBorder}, {{w, h}, kImageBorder}, {{0, h}, kImageBorder}};
  if (shoelace(frame) < 0) std::reverse(frame.begin(), frame.end());
  Tracer tracer(wp, camera, options);
  tracer.trace(start, frame, map);
  build_planar_map(map, tracer);
  map.stats.ms = watch.elapsed_ms();
  return map;
}

ImageU32 rasterize_map(const VisibilityMap& map) {
  ImageU32 out(map.width, map.height, 1, kNone);
  for (const MapRegion& r : map.regions) {
    double ymin = INFINITY, ymax = -INFINITY;
    for (const dvec2& p : r.vertices) {
      ymin = std::min(ymin, p.y);
      ymax = std::max(ymax, p.y);
    }
    const int y0 = std::max(0, int(std::ceil(ymin - 0.5))), y1 = std::min(map.height - 1, int(std::floor(ymax - 0.5)));
    for (int y = y0; y <= y1; ++y) {
      const double cy = y + 0.5;
      double xl = INFINITY, xr = -INFINITY;
      const size_t n = r.vertices.size();
      for (size_t i = 0; i < n; ++i) {
        const dvec2 a = r.vertices[i], b = r.vertices[(i + 1) % n];
        if ((a.y <= cy && b.y >= cy) || (b.y <= cy && a.y >= cy)) {
          double x = a.y == b.y ? a.x : a.x + (b.x - a.x) * (cy - a.y) / (b.y - a.y);
          if (a.y == b.y) {
            xl = std::min({xl, a.x, b.x});
            xr = std::max({xr, a.x, b.x});
          }
          xl = std::min(xl, x);
          xr = std::max(xr, x);
        }
      }
      const int x0 = std::max(0, int(std::ceil(xl - 0.5))), x1 = std::min(map.width, int(std::ceil(xr - 0.5)));
      for (int x = x0; x < x1; ++x) out.at(x, y) = r.polygon;
    }
  }
  return out;
}

double region_area(const MapRegion& region) {
  const std::vector<dvec2>& v = region.vertices;
  double a = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    const dvec2 p = v[i], q = v[(i + 1) % v.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

ImageU8 map_edge_mask(const VisibilityMap& map, double radius) {
  ImageU8 mask(map.width, map.height, 1, 0);
  for (const MapEdge& e : map.edges) {
    if (e.source == kImageBorder) continue;
    const uint32_t pl = e.region[0] == kNone ? kNone - 1 : map.regions[e.region[0]].polygon;
    const uint32_t pr = e.region[1] == kNone ? kNone - 1 : map.regions[e.region[1]].polygon;
    if (pl == pr) continue;
    const dvec2 a = map.vertices[e.vertex[0]], b = map.vertices[e.vertex[1]];
    const dvec2 d = b - a;
    const double len2 = std::max(glm::dot(d, d), 1e-300);
    const int steps = int(std::ceil(std::sqrt(len2) / 0.5)) + 1;
    const int reach = int(std::ceil(radius)) + 1;
    for (int s = 0; s <= steps; ++s) {
      const dvec2 p = a + d * (double(s) / steps);
      const int px = int(std::floor(p.x)), py = int(std::floor(p.y));
      for (int y = py - reach; y <= py + reach; ++y)
        for (int x = px - reach; x <= px + reach; ++x) {
          if (x < 0 || y < 0 || x >= map.width || y >= map.height) continue;
          const dvec2 c(x + 0.5, y + 0.5);
          const double t = std::clamp(glm::dot(c - a, d) / len2, 0.0, 1.0);
          if (glm::length(c - (a + d * t)) <= radius) mask.at(x, y) = 1;
        }
    }
  }
  return mask;
}

}  // namespace proxima::visibility
