// Brush-built game levels (`level-*` built-in scenes): the geometry a Quake / Hammer /
// Radiant level editor exports, generated procedurally. Every solid is a convex brush (box,
// wedge, n-sided prism) emitted as its own object with its own vertices, and nothing is
// cut against anything else (no CSG), so the triangles carry what real levels carry and the
// synthetic visibility models do not:
// - coplanar overlapping faces: adjacent floor slabs overlap under the walls, lintels
//   overlap their door posts, decals lie on walls;
// - T-junctions: walls end on the middle of other walls and slabs, lintels abut posts,
//   steps abut steps, wedges end on walls;
// - interpenetrating brushes: wall corners, columns sunk into slabs, crates in crates;
// - unwelded seams: no vertex is shared between brushes; a brush's corners come either from
//   its bounds or from center ± half size (float rounding differs by an ulp), and a seam is
//   moved by ±`seam_jitter` (a gap or an overlap of ~0.1 mm) with probability 1/4;
// - open meshes: brush faces resting on other brushes dropped ("nodraw"), single-quad
//   decals, angled walls without a top;
// - slivers and mixed scales: 2 cm trims and baseboards beside 8 m slabs.
//
// Layout (meters, +Y up): `floors` storeys 3.5 m apart of rooms_x × rooms_z rooms of
// 8 × 7 m on a grid (room (i, j) spans x ∈ [8i, 8i + 8], z ∈ [7j, 7j + 7]), 0.2 m walls on
// the grid lines, 0.25 m slabs whose top is the floor. Doors (1.2 × 2.4 m, at the middle of
// a wall) join the rooms of a storey as a random spanning tree plus a few extra doors. A
// ramp (even storeys) or a flight of 14 steps (odd storeys) climbs from storey f to f + 1
// in room (1, 0) or (1, rooms_z − 1) alternately, under a hole in the slab above. Each
// room's four quadrants (off the cross between its doors) hold an octagonal or rotated
// column, crates, a platform with a wedge, an angled wall across the corner, or nothing.
//
// Camera path "walk" (150 frames, 75° vertical fov): from room (0, 0) through the doors of
// storey 0 (a depth-first tour to depth 2 and back), up the ramp of room (1, 0), on through
// the doors of storey 1. Eyes are 1.6 m above the floor or ramp, at room centers, door
// centers and along the ramp: in open space by construction (tests/scene/level_scenes_test
// checks it with Embree rays).
#pragma once

#include <cstdint>
#include <string>

#include "proxima/scene/scene.h"

namespace proxima {

struct LevelOptions {
  std::string name = "level";
  int rooms_x = 3;   // ≥ 3 (the ramp room is (1, 0), with a room on each side)
  int rooms_z = 3;   // ≥ 3 (so storeys stay connected around the ramp rooms)
  int floors = 2;    // ≥ 2 (the walk climbs from storey 0 to 1)
  int detail = 1;    // 0: walls, slabs, ramps, quadrant features; 1: plus door trims,
                     // baseboards, lights, decals, railings
  float seam_jitter = 1e-4f;  // meters a jittered seam moves (0 = every seam exact)
  uint64_t seed = 1;
};

// Builds the level; throws InputError for options out of range.
Scene make_level(const LevelOptions& options);

// The named sizes (triangle counts in docs/visibility.md):
// level-small  3 × 3 rooms, 2 storeys, detail 0  (2,684 triangles, 1,314 polygons)
// level-medium 4 × 3 rooms, 2 storeys, detail 1  (6,104 triangles, 2,992 polygons)
// level-large  6 × 4 rooms, 3 storeys, detail 1  (18,994 triangles, 9,348 polygons)
// level-huge   8 × 8 rooms, 3 storeys, detail 1  (50,884 triangles, 25,089 polygons)
bool is_level_scene(const std::string& name);
LevelOptions level_options(const std::string& name);  // InputError for an unknown name

}  // namespace proxima
