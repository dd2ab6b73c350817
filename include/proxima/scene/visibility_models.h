// The procedural test models of the exact-visibility paper (Funkhouser, section 5, Figure 7),
// built as axis-aligned or rotated quads (2 triangles each, merged back into one polygon by
// visibility::extract_polygons) and 5-sided boxes (no bottom). Each has a camera path
// "walk" of ≥ 100 frames. Polygon counts after merging (docs/visibility.md):
// - rooms: 2 rooms joined by a door in a 0.2 m thick wall, 20 polygons.
// - maze: 17 × 17 perfect maze (seeded) of 2 m cells on a jittered grid rotated 25°,
//   single-sided-thin walls 2.5 m high, open sky, ~325 polygons; path = the solution.
// - arena: 40 × 40 m hall, 6 m walls, 130 boxes at random yaw and 2 platforms, ~667 polygons;
//   path = a loop around the hall.
// - vcity: 15 × 15 box buildings on a 12 m grid and a ground plane, 1,126 polygons;
//   path = a flight 8 m above the streets.
// - floor: an office floor, 2 × 30 offices (door wall, partition, 5 furniture boxes) on a
//   corridor, ~1,750 polygons; path = along the corridor and into two offices.
// - building: `floors` office floors (2 × 32 offices each) 3.2 m apart, joined by a
//   stairwell (slab holes, 12-step stairs), ~1,940 polygons per floor (~9,700 for 5);
//   path = the floor-1 (ground floor) walk.
#pragma once

#include <string>

#include "proxima/scene/scene.h"

namespace proxima {

Scene make_vis_rooms();
Scene make_vis_maze();
Scene make_vis_arena();
Scene make_vis_vcity();
Scene make_vis_floor();
// floors in [1, 64]; throws InputError otherwise.
Scene make_vis_building(int floors = 5);
// Thin occluders in front of a wall: a room whose back wall is seen through a row of thin
// columns and a railing bar (GIBR's silhouette test scene, docs/gibr.md), 57 polygons.
Scene make_vis_colonnade();
// Thin high-contrast occluders: a dark iron railing (61 balusters 3 cm square, two rails) in
// front of a bright facade, lit from high in front so the railing's shadows fall on the
// balcony's floor (scene/balcony_scene.cpp; GIBR's thin-occluder regime), 262 polygons.
Scene make_vis_balcony();

// True for the names of the models above (rooms, maze, arena, vcity, floor, building,
// building:N, colonnade, balcony) and the brush-built levels (level-*, scene/level_scenes.h): the scenes the
// exact-visibility pipeline (and GIBR) is made for.
bool is_visibility_model(const std::string& scene_name);

}  // namespace proxima
