// Winged-pair traversal helpers (Funkhouser, section 3, Figures 4–5): face loops from clock
// links, cell face lists from the faces' cell references, point location.
#include "proxima/visibility/winged_pair.h"

#include <cmath>

namespace proxima::visibility {

bool finalize(WingedPair& wp) {
  wp.loop_offset.assign(1, 0);
  wp.loop_vertex.clear();
  wp.loop_edge.clear();
  // A pair is on one face's loop: a walk meeting a pair seen before does not close (and
  // without the check a hostile file could make the walks quadratic in the pair count).
  std::vector<bool> seen(wp.pairs.size(), false);
  for (uint32_t f = 0; f < wp.faces.size(); ++f) {
    uint32_t p = wp.faces[f].pair;
    for (;;) {
      if (p >= wp.pairs.size() || seen[p] || wp.pairs[p].face != f || wp.pairs[p].edge >= wp.edges.size())
        return false;
      seen[p] = true;
      const Pair& pr = wp.pairs[p];
      const Edge& e = wp.edges[pr.edge];
      wp.loop_vertex.push_back(pr.direction ? e.vertex[0] : e.vertex[1]);
      wp.loop_edge.push_back(pr.edge);
      p = pr.clock[0];
      if (p == wp.faces[f].pair) break;
    }
    wp.loop_offset.push_back(uint32_t(wp.loop_vertex.size()));
  }
  std::vector<uint32_t> count(wp.cells.size() + 1, 0);
  for (const Face& f : wp.faces)
    for (uint32_t c : f.cell) {
      if (c == kNone) continue;
      if (c >= wp.cells.size()) return false;
      ++count[c + 1];
    }
  for (size_t c = 0; c < wp.cells.size(); ++c) count[c + 1] += count[c];
  wp.cell_face_offset = count;
  wp.cell_face.assign(count.back(), kNone);
  for (uint32_t f = 0; f < wp.faces.size(); ++f)
    for (uint32_t c : wp.faces[f].cell)
      if (c != kNone) wp.cell_face[count[c]++] = f;
  wp.cell_lo.assign(wp.cells.size(), dvec3(INFINITY));
  wp.cell_hi.assign(wp.cells.size(), dvec3(-INFINITY));
  for (uint32_t f = 0; f < wp.faces.size(); ++f)
    for (uint32_t c : wp.faces[f].cell) {
      if (c == kNone) continue;
      for (uint32_t i = wp.loop_offset[f]; i < wp.loop_offset[f + 1]; ++i) {
        const dvec3& p = wp.vertices[wp.loop_vertex[i]].position;
        wp.cell_lo[c] = glm::min(wp.cell_lo[c], p);
        wp.cell_hi[c] = glm::max(wp.cell_hi[c], p);
      }
    }
  return true;
}

namespace {

bool contains(const WingedPair& wp, uint32_t c, const dvec3& p) {
  const double tol = 1e-9 * wp.scale;
  // The bounding box first: a cheap rejection of almost every cell.
  if (glm::any(glm::lessThan(p, wp.cell_lo[c] - dvec3(tol))) || glm::any(glm::greaterThan(p, wp.cell_hi[c] + dvec3(tol))))
    return false;
  for (uint32_t f : wp.faces_of_cell(c)) {
    const Face& face = wp.faces[f];
    const double d = face.plane.distance(p);
    // The cell is behind (cell[0]) or in front of (cell[1]) the face plane.
    if (face.cell[0] == c ? d > tol : d < -tol) return false;
  }
  return !wp.faces_of_cell(c).empty();
}

}  // namespace

uint32_t locate_cell(const WingedPair& wp, const dvec3& p) {
  for (uint32_t c = 0; c < wp.cells.size(); ++c)
    if (contains(wp, c, p)) return c;
  return kNone;
}

std::vector<uint32_t> locate_cells(const WingedPair& wp, const dvec3& p) {
  std::vector<uint32_t> out;
  for (uint32_t c = 0; c < wp.cells.size(); ++c)
    if (contains(wp, c, p)) out.push_back(c);
  return out;
}

}  // namespace proxima::visibility
