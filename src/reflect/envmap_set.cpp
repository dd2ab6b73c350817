#include "proxima/reflect/envmap_set.h"

#include "proxima/core/timer.h"
#include "proxima/reflect/envmap_lookup.h"

namespace proxima {

EnvmapSet build_envmap_set(const Scene& scene, const RayScene& rays, std::span<const uint32_t> reflectors,
                           const EnvmapSetOptions& o) {
  EnvmapSet set;
  Stopwatch w;
  set.groups = group_reflectors(scene, rays, reflectors, o.grouping);
  set.group_ms = w.elapsed_ms();
  set.group_of = envmap_group_of_objects(scene, set.groups);
  set.maps.resize(set.groups.size());
  DistanceCubeMapOptions mo = o.map;
  for (size_t g = 0; g < set.groups.size(); ++g) {
    const EnvmapGroup& group = set.groups[g];
    EnvmapMaps& maps = set.maps[g];
    mo.exclude = group.reflectors;
    if (o.single) {
      w.restart();
      maps.map = render_distance_cube_map(scene, rays, group.center, mo);
      set.map_ms += w.elapsed_ms();
      if (o.average_step_rad > 0.0f) {
        w.restart();
        maps.average_distance = average_distance(maps.map, o.average_step_rad);
        set.average_ms += w.elapsed_ms();
      }
    }
    if (o.layers > 0) {
      DistanceCubeLayerOptions lo = o.layer;
      lo.layers = o.layers;
      lo.viewer_radius = group.radius;
      w.restart();
      maps.layers = render_distance_cube_layers(scene, rays, group.center, mo, lo);
      set.layers_ms += w.elapsed_ms();
    }
  }
  return set;
}

}  // namespace proxima
