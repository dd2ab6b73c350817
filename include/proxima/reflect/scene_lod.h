// Levels of detail of a scene for small images: vertex clustering per object (Rossignac and
// Borrel 1993). At level L ≥ 1 every vertex of an object moves to the representative of
// its cell of a grid with cell size cell[L − 1] (the lowest-index vertex of the object in
// that cell); triangles that lose a vertex that way vanish, duplicates are dropped. The
// surviving triangles keep their source triangle's id for shading and their orientation.
// Level 0 is the scene itself. The representatives are chosen in the rest pose and are
// existing vertices, so a rigidly posed scene's positions serve every level unchanged.
//
// A cluster image of a reflection whose texels cover centimetres does not need the
// millimetre triangles of a cushion's seams: drawn at the level whose cell is at most a
// fraction of a texel's footprint, the image differs from the exact one by at most about
// that fraction of a texel in position (docs/cluster_reflections.md, "Level of detail").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/scene/scene.h"

namespace proxima {

struct SceneLod {
  uint32_t source_objects = 0;             // objects of the source scene
  std::vector<float> cell;                 // per level ≥ 1 (index L − 1): grid cell, meters
  // Every level's triangles, level by level and object by object: object L·source_objects + o
  // of `objects` is level L of source object o (first_triangle, triangle_count index
  // `triangles`; first_vertex, vertex_count as the source object's).
  std::vector<Object> objects;
  std::vector<uvec3> triangles;            // vertex indices into the source scene's positions
  std::vector<uint32_t> triangle_object;   // per triangle: its object in `objects`
  std::vector<uint32_t> source_triangle;   // per triangle: the source triangle it stands for

  uint32_t levels() const { return uint32_t(cell.size()) + 1; }
  // Index in `objects` of source object o at level L.
  uint32_t object(uint32_t level, uint32_t o) const { return level * source_objects + o; }
};

// Levels 0 … cells.size() of `rest` (cells in meters, ascending).
SceneLod build_scene_lod(const Scene& rest, std::span<const float> cells);

// Cells scene_diagonal·2^(L − 12) for L = 1 … levels − 1: from 1/2048 of the diagonal up.
std::vector<float> lod_cells(float scene_diagonal, int levels);

// A scene to rasterize the levels with: `posed`'s positions (the source scene, posed), the
// levels' triangles and objects. Triangle ids in its images index SceneLod::triangles.
Scene lod_draw_scene(const SceneLod& lod, const Scene& posed);

}  // namespace proxima
