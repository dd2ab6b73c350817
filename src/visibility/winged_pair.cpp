// Winged-pair traversal helpers (Funkhouser, section 3, Figures 4–5): face loops from clock
// links, cell face lists from the faces' cell references, point location.
#include "proxima/visibility/winged_pair.h"

#include <algorithm>
#include <cmath>

namespace proxima::visibility {
namespace {

// Median split of the cells' box centers along the widest axis, ≤ 4 cells a leaf; iterative
// (explicit stack), deterministic (nth_element on the index order, ties by cell id).
void build_cell_tree(WingedPair& wp) {
  wp.tree.clear();
  wp.tree_cell.clear();
  for (uint32_t c = 0; c < wp.cells.size(); ++c)
    if (wp.cell_face_offset[c + 1] > wp.cell_face_offset[c]) wp.tree_cell.push_back(c);
  if (wp.tree_cell.empty()) return;
  auto center = [&](uint32_t c) { return 0.5 * (wp.cell_lo[c] + wp.cell_hi[c]); };
  // Sort key along an axis; NaN (a corrupt file) → −inf, keeping the order strict-weak.
  auto key = [&](uint32_t c, int axis) {
    const double x = center(c)[axis];
    return std::isnan(x) ? -INFINITY : x;
  };
  wp.tree.push_back({dvec3(0.0), dvec3(0.0), 0, uint32_t(wp.tree_cell.size()), {kNone, kNone}});
  std::vector<uint32_t> todo = {0};
  while (!todo.empty()) {
    const uint32_t n = todo.back();
    todo.pop_back();
    const uint32_t first = wp.tree[n].first, count = wp.tree[n].count;
    dvec3 lo(INFINITY), hi(-INFINITY), clo(INFINITY), chi(-INFINITY);
    for (uint32_t i = first; i < first + count; ++i) {
      const uint32_t c = wp.tree_cell[i];
      lo = glm::min(lo, wp.cell_lo[c]);
      hi = glm::max(hi, wp.cell_hi[c]);
      clo = glm::min(clo, center(c));
      chi = glm::max(chi, center(c));
    }
    wp.tree[n].lo = lo;
    wp.tree[n].hi = hi;
    if (count <= 4) continue;
    const dvec3 ext = chi - clo;
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
    const uint32_t half = count / 2;
    auto begin = wp.tree_cell.begin() + first;
    std::nth_element(begin, begin + half, begin + count, [&](uint32_t a, uint32_t b) {
      const double ca = key(a, axis), cb = key(b, axis);
      return ca < cb || (ca == cb && a < b);
    });
    const uint32_t left = uint32_t(wp.tree.size());
    wp.tree[n].child[0] = left;
    wp.tree[n].child[1] = left + 1;
    wp.tree[n].count = 0;
    wp.tree.push_back({dvec3(0.0), dvec3(0.0), first, half, {kNone, kNone}});
    wp.tree.push_back({dvec3(0.0), dvec3(0.0), first + half, count - half, {kNone, kNone}});
    todo.push_back(left);
    todo.push_back(left + 1);
  }
}

}  // namespace

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
  wp.opaque_lo = dvec3(INFINITY);
  wp.opaque_hi = dvec3(-INFINITY);
  for (uint32_t f = 0; f < wp.faces.size(); ++f) {
    if (!wp.faces[f].opaque()) continue;
    for (uint32_t i = wp.loop_offset[f]; i < wp.loop_offset[f + 1]; ++i) {
      wp.opaque_lo = glm::min(wp.opaque_lo, wp.vertices[wp.loop_vertex[i]].position);
      wp.opaque_hi = glm::max(wp.opaque_hi, wp.vertices[wp.loop_vertex[i]].position);
    }
  }
  build_cell_tree(wp);
  return true;
}

bool cell_contains(const WingedPair& wp, uint32_t c, const dvec3& p) {
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

uint32_t locate_cell(const WingedPair& wp, const dvec3& p) {
  const std::vector<uint32_t> cells = locate_cells(wp, p);
  return cells.empty() ? kNone : cells.front();
}

std::vector<uint32_t> locate_cells(const WingedPair& wp, const dvec3& p) {
  std::vector<uint32_t> out;
  if (wp.tree.empty()) return out;
  const double tol = 1e-9 * wp.scale;
  uint32_t stack[128];  // depth ≤ log2(cells) + 1 (median splits)
  size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const WingedPair::TreeNode& node = wp.tree[stack[--top]];
    if (glm::any(glm::lessThan(p, node.lo - dvec3(tol))) || glm::any(glm::greaterThan(p, node.hi + dvec3(tol))))
      continue;
    if (node.child[0] == kNone) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i)
        if (cell_contains(wp, wp.tree_cell[i], p)) out.push_back(wp.tree_cell[i]);
    } else {
      stack[top++] = node.child[0];
      stack[top++] = node.child[1];
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace proxima::visibility
