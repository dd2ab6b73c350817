// The winged-pair structure (Funkhouser, section 3, Figure 4): a 3-manifold cell complex
// of convex polyhedral cells glued along convex faces. One Pair per (face, edge) incidence
// carries the traversal links: clock[] around the face, spin[] around the edge.
//
// Conventions (all indices are into the WingedPair arrays; kNone = absent):
// - Face plane: dot(normal, x) + offset = 0, normal unit. cell[0] lies on the negative side
//   (behind), cell[1] on the positive side (in front); kNone on the outside of the outer box.
// - A face's boundary, walked by clock[0], is counter-clockwise seen from the front.
// - Pair::direction = 1 when that counter-clockwise walk traverses the edge from
//   vertex[0] to vertex[1], 0 when from vertex[1] to vertex[0].
// - spin[0] is the next face around the edge counter-clockwise seen from vertex[1]
//   looking toward vertex[0] (right-handed about vertex[1] − vertex[0]); spin[1] the previous.
// - Face::polygon is the input polygon id of an opaque face (it lies on that polygon),
//   kNone for a transparent face (free space).
// Coordinates are world meters, double precision.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "proxima/visibility/polygons.h"

namespace proxima::visibility {

struct Vertex {
  dvec3 position{0.0};
  uint32_t edge = kNone;  // one attached edge
};

struct Edge {
  uint32_t vertex[2] = {kNone, kNone};
  uint32_t pair = kNone;  // one attached face-edge pair
};

struct Face {
  uint32_t cell[2] = {kNone, kNone};  // behind, in front (see above)
  uint32_t pair = kNone;              // one attached face-edge pair
  uint32_t polygon = kNone;           // opaque: input polygon id; transparent: kNone
  Plane plane;

  bool opaque() const { return polygon != kNone; }
};

struct Cell {
  uint32_t face = kNone;  // one attached face
};

struct Pair {
  uint32_t face = kNone;
  uint32_t edge = kNone;
  uint32_t clock[2] = {kNone, kNone};  // next pair around the face: [0] ccw, [1] cw
  uint32_t spin[2] = {kNone, kNone};   // next pair around the edge: [0] ccw, [1] cw
  uint8_t direction = 0;
};

struct WingedPair {
  std::vector<Vertex> vertices;
  std::vector<Edge> edges;
  std::vector<Face> faces;
  std::vector<Cell> cells;
  std::vector<Pair> pairs;
  uint32_t polygon_count = 0;  // input polygons the opaque faces refer to
  double scale = 1.0;          // model scale (meters) the tolerances are relative to

  // Derived by finalize() from the records above (walks clock links), for fast traversal:
  // the counter-clockwise vertex and edge loop of each face, and the faces of each cell.
  std::vector<uint32_t> loop_offset, loop_vertex, loop_edge;  // face f: [loop_offset[f], [f+1])
  std::vector<uint32_t> cell_face_offset, cell_face;          // cell c: [offset[c], [c+1])
  std::vector<dvec3> cell_lo, cell_hi;  // each cell's bounding box (fast point location)
  // The bounding box of the opaque faces' vertices (empty: lo > hi when there are none): a
  // sightline that has left it through one of its sides meets no opaque face any more.
  dvec3 opaque_lo{INFINITY}, opaque_hi{-INFINITY};
  // A bounding-volume tree over the cell boxes: O(log n) point location instead of a scan
  // of every cell (the scan grew with `building --floors`). Leaves hold ≤ 4 cells of
  // `tree_cell`; cells without faces are left out (they contain no point).
  struct TreeNode {
    dvec3 lo{0.0}, hi{0.0};
    uint32_t first = 0, count = 0;  // leaf: tree_cell[first, first + count)
    uint32_t child[2] = {kNone, kNone};
  };
  std::vector<TreeNode> tree;  // tree[0] = root (empty when there are no cells)
  std::vector<uint32_t> tree_cell;

  std::span<const uint32_t> face_vertices(uint32_t f) const {
    return {loop_vertex.data() + loop_offset[f], loop_offset[f + 1] - loop_offset[f]};
  }
  std::span<const uint32_t> face_edges(uint32_t f) const {
    return {loop_edge.data() + loop_offset[f], loop_offset[f + 1] - loop_offset[f]};
  }
  std::span<const uint32_t> faces_of_cell(uint32_t c) const {
    return {cell_face.data() + cell_face_offset[c], cell_face_offset[c + 1] - cell_face_offset[c]};
  }
  // The cell on the other side of `face` from `cell` (paper: CellAcrossFace).
  uint32_t cell_across(uint32_t face, uint32_t cell) const {
    return faces[face].cell[0] == cell ? faces[face].cell[1] : faces[face].cell[0];
  }
};

// Fills the derived arrays. Returns false (leaving them partial) when a clock walk does
// not close within the pair count or a face names a cell out of range.
bool finalize(WingedPair& wp);

// Whether cell c's closed interior contains p within the model tolerance (1e-9 · scale).
bool cell_contains(const WingedPair& wp, uint32_t c, const dvec3& p);

// The cell whose closed interior contains p within the model tolerance (first in index
// order when p lies on a shared face); kNone outside the outer box. Both lookups descend
// the cell tree (the same cells as testing every cell, in index order).
uint32_t locate_cell(const WingedPair& wp, const dvec3& p);

// Every cell whose closed interior contains p within the model tolerance: one for a point
// inside a cell, 2 or more for a point on a face, edge or vertex; empty outside the box.
std::vector<uint32_t> locate_cells(const WingedPair& wp, const dvec3& p);

}  // namespace proxima::visibility
