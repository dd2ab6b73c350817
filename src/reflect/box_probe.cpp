#include "proxima/reflect/box_probe.h"

#include <cmath>

#include "proxima/scene/light.h"

namespace proxima {

Bounds3 probe_proxy_box(const Scene& scene) { return scene.probe_box.empty() ? scene_bounds(scene) : scene.probe_box; }

std::optional<vec3> box_exit_point(const Bounds3& box, vec3 x, vec3 dir) {
  // Slab test: the ray leaves the box at the smallest of the per-axis far-plane distances.
  float t_exit = kInf, t_enter = -kInf;
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0f) {
      if (x[a] < box.min[a] || x[a] > box.max[a]) return std::nullopt;
      continue;
    }
    const float t0 = (box.min[a] - x[a]) / dir[a], t1 = (box.max[a] - x[a]) / dir[a];
    t_enter = std::max(t_enter, std::min(t0, t1));
    t_exit = std::min(t_exit, std::max(t0, t1));
  }
  if (!(t_exit > 0.0f) || !(t_exit >= t_enter) || !std::isfinite(t_exit)) return std::nullopt;
  return x + t_exit * dir;
}

EnvLookup box_probe_lookup(const DistanceCubeMap& map, const Environment& env, vec3 x, vec3 dir,
                           const Bounds3& box) {
  const std::optional<vec3> hit = box_exit_point(box, x, dir);
  if (!hit) return plain_lookup(map, env, dir);
  EnvLookup r;
  const vec3 l1 = *hit - map.camera.center;
  const CubeSample s = sample_cube(map, l1);
  r.steps = 1;
  r.query = *hit;
  r.saw_inf = r.miss = s.empty;
  r.color = s.empty ? environment_radiance(env, dir) : s.color;
  r.object = s.object;
  return r;
}

}  // namespace proxima
