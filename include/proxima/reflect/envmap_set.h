// The maps the env-map methods read on a scene with any number of reflectors: the
// reflectors grouped (envmap_groups.h), and per group a distance cube map (plain, rectified,
// average, box probe; with its average distance d̄) and/or K depth layers (layered), each
// around the group's center with the group's own reflectors left out. Built once for a
// static environment; EnvmapInputs reads it per reflector pixel or sample by object.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/reflect/distance_cube_map.h"
#include "proxima/reflect/envmap_groups.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

struct EnvmapSetOptions {
  EnvmapGroupOptions grouping;
  DistanceCubeMapOptions map;       // resolution, light samples, seed, shading; `exclude` is set per group
  bool single = true;               // each group's distance cube map
  float average_step_rad = 0.0f;    // > 0 (with single): each map's average distance d̄, sampled at this step
  int layers = 0;                   // > 0: K depth layers per group
  DistanceCubeLayerOptions layer;   // for the layers; `layers` and `viewer_radius` (the group's) are set per group
};

struct EnvmapSet {
  std::vector<EnvmapGroup> groups;
  std::vector<uint32_t> group_of;  // per object id, its group (kNoEnvmapGroup: none)
  std::vector<EnvmapMaps> maps;    // per group
  // Build times, wall clock, summed over the groups.
  double group_ms = 0.0, map_ms = 0.0, average_ms = 0.0, layers_ms = 0.0;
};

// Groups `reflectors` (object ids) and renders each group's maps. `rays` must hold `scene`.
// Throws InputError for invalid grouping or map options.
EnvmapSet build_envmap_set(const Scene& scene, const RayScene& rays, std::span<const uint32_t> reflectors,
                           const EnvmapSetOptions& options);

// `inputs` reading the set's maps (which must outlive them).
inline EnvmapInputs with_envmap_set(EnvmapInputs inputs, const EnvmapSet& set) {
  inputs.groups = set.maps;
  inputs.group_of = set.group_of;
  return inputs;
}

}  // namespace proxima
