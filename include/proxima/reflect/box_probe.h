// Box-projected (parallax-corrected) cube maps — Lagarde & Zanuttini 2012, "Local image-based
// lighting with parallax-corrected cubemaps"; Unity's Box Projection, Unreal's box reflection
// captures: the reflected ray x + t·l̂ is intersected with a proxy box around the probe, and
// the cube map is looked up in the direction of that hit as seen from the probe's center c.
// One ray–box test per lookup; exact where the environment's surfaces lie on the box.
#pragma once

#include <optional>

#include "proxima/core/math.h"
#include "proxima/reflect/distance_cube_map.h"
#include "proxima/reflect/envmap_lookup.h"
#include "proxima/scene/scene.h"

namespace proxima {

// The proxy box of the scene's probes: the scene file's `probe_box` when given, else the
// scene's bounds (the room around the probe).
Bounds3 probe_proxy_box(const Scene& scene);

// Exit point of the ray x + t·dir (t > 0) from `box`; nullopt when the ray never reaches the
// box's far side in front of x (x outside the box and moving away), or dir is 0 or NaN.
std::optional<vec3> box_exit_point(const Bounds3& box, vec3 x, vec3 dir);

// The texel of `map` in the direction (exit point − c); the plain lookup along dir where the
// ray has no exit point, environment_radiance(dir) where the texel is empty (miss = true).
EnvLookup box_probe_lookup(const DistanceCubeMap& map, const Environment& env, vec3 x, vec3 dir,
                           const Bounds3& box);

}  // namespace proxima
