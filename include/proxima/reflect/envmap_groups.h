// Which reflectors share an environment map. One map is exact only for rays that start at
// its projection center c; a reflector point at distance r from c sees a surface at
// distance d under a parallax of about r/d (plain lookups are off by that angle, and the
// rectified search fails where the surfaces seen from c and from the point differ, which
// grows with the same ratio). So each reflector gets its own map, centred at it, as the
// distance impostors of Szirmay-Kalos, Aszódi, Lazányi and Premecz ("Approximate
// ray-tracing on the GPU with distance impostors", 2005) do — and reflectors close together
// relative to their surroundings share one, which bounds the number of maps on scenes with
// many reflecting objects. A group's map leaves out only that group's reflectors: the other
// reflectors are part of its environment (shaded one bounce deep, as the reference at its
// bounce limit), so reflectors see each other.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/core/math.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

struct EnvmapGroupOptions {
  // Two groups are merged while the merged group's parallax (EnvmapGroup::parallax) is at
  // most this: its reflectors lie close together compared with the surfaces around them.
  float max_parallax = 0.2f;
  // At most this many groups (maps): beyond it, the pair whose merged group is most compact
  // (smallest radius) is merged whatever its parallax. 1 = one map shared by every reflector.
  int max_groups = 4;
};
inline constexpr int kMaxEnvmapGroups = 64;
// Throws InputError naming --max-maps (max_groups outside 1..kMaxEnvmapGroups) or
// --group-parallax (max_parallax negative or not finite).
void validate(const EnvmapGroupOptions& options);

struct EnvmapGroup {
  std::vector<uint32_t> reflectors;  // object ids, ascending
  vec3 center{0.0f};                 // projection center: the center of their combined bounds
  float radius = 0.0f;               // largest distance of a vertex of theirs from center (viewer_radius)
  // Mean over kGroupProbeDirections directions from center of min(1, radius / d), d the
  // distance along the direction to the first surface that is not one of the group's
  // reflectors (0 where the ray escapes): the mean parallax of the group's map.
  float parallax = 0.0f;
};
inline constexpr int kGroupProbeDirections = 128;

// Agglomerative grouping of `reflectors` (object ids), from one group per reflector:
// (1) repeatedly merges the pair whose merged group has the smallest parallax while that is
// ≤ max_parallax; (2) while there are more than max_groups groups, merges the pair whose
// merged group has the smallest radius (from the objects' bounding boxes): the parallax
// saturates at 1 for groups inside or against their surroundings, the radius still tells
// reflectors close together from ones far apart. Candidate merges are judged with a radius
// from the objects' bounding boxes (≥ the vertices'; conservative). Groups come ordered by
// their smallest object id. Deterministic for any thread count. `rays` must hold `scene`.
// Throws InputError for invalid options (validate).
std::vector<EnvmapGroup> group_reflectors(const Scene& scene, const RayScene& rays,
                                          std::span<const uint32_t> reflectors, const EnvmapGroupOptions& options);

// The group of one set of reflectors, ungrouped (its center, radius and parallax).
EnvmapGroup make_envmap_group(const Scene& scene, const RayScene& rays, std::vector<uint32_t> reflectors);

// Per object id, the index of its group in `groups`; kNoEnvmapGroup for objects in none.
inline constexpr uint32_t kNoEnvmapGroup = 0xFFFFFFFFu;
std::vector<uint32_t> envmap_group_of_objects(const Scene& scene, std::span<const EnvmapGroup> groups);

}  // namespace proxima
