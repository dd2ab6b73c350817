// Built-in procedural scenes, deterministic, listed by `proxima scenes`.
#pragma once

#include <string>
#include <vector>

#include "proxima/scene/scene.h"

namespace proxima {

struct BuiltinSceneInfo {
  std::string name;
  std::string description;
};

// cornell, room-reflector, living-room, bathroom, in that order:
// - cornell: interior x ∈ [−1, 1], y ∈ [0, 2], z ∈ [−1, 1], open at z = +1; inward walls
//   of 8 × 8 quads; mirror sphere r 0.4 at (−0.4, 0.4, −0.2); glossy 0.5 × 1 × 0.5 block at
//   (0.45, 0.5, −0.35) turned 20° about +Y; 0.5 × 0.5 area light facing down at y = 1.98
//   (plus an emissive quad "light" at y = 1.985); camera "front". Analytic tests rely on
//   this layout: do not change it.
// - room-reflector: 8 × 8 × 4 m room with a 2,176-triangle mirror cylinder at its center.
// - living-room: ~290k triangles, ~135k of them on 24 reflectors; cameras "overview",
//   "table"; paths "walk", "orbit".
// - bathroom: ~93k triangles, ~50k on 26 reflectors; cameras "door", "mirror"; paths
//   "walk", "pan".
// For environment maps with distance:
// - room-teapot: room-reflector with a 39,800-triangle mirror teapot instead of the cylinder.
// - room-car: room-reflector with a 39,936-triangle car-like mirror body (two
//   superellipsoids) instead of the cylinder.
// - room-parallax: the room with a mirror cylinder and a red sphere between it and the
//   checkered front wall; cameras "left", "right" (the layered env-map parallax test).
std::vector<BuiltinSceneInfo> builtin_scenes();

bool is_builtin_scene(const std::string& name);

// Builds a built-in scene; throws InputError for an unknown name (listing the known ones).
Scene make_builtin_scene(const std::string& name);

}  // namespace proxima
