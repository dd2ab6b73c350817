// The built-in scenes of the depth-image sampling chapter (thesis ch. 2, Tables 2–7),
// procedural and deterministic (fixed seeds), near the thesis' triangle counts. Each has
// one camera "main" framing the object, one point light, ambient light; every surface is
// diffuse. Thin parts (grass blades, leaves) are double-sided: triangles of opposite
// winding 1 mm apart, so they survive back-face culling from either side.
#pragma once

#include "proxima/scene/scene.h"

namespace proxima {

// Bird nest: ~67k triangles, ~5,500 thin tapered twigs (6-sided open tubes) interwoven in
// a bowl of radius 1 m on a ground plane.
Scene make_nest_scene();

// Grass: ~56k triangles, 4,660 curved double-sided blades (0.2–0.6 m, 12 triangles each)
// on a 4 × 4 m patch. `blades` changes the density on the same patch (the first blades
// are the same for any count): the growing grass of thesis Figure 20.
inline constexpr int kGrassBlades = 4660;
Scene make_grass_scene(int blades = kGrassBlades);

// City: ~50k triangles, a 64 × 64 grid of box buildings (12 triangles each, heights
// 0.5–6 m on 1 m lots with 0.4 m streets) on a ground plane.
Scene make_city_scene();

// Tree: ~113k triangles, a recursively branching trunk (tapered tubes) carrying ~25k
// double-sided leaves.
Scene make_tree_scene();

}  // namespace proxima
