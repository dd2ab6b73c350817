// Lookups with position rectification — Wang, Tang, Sun, Ma, "Environment mapping with
// position rectification", J. Image and Graphics 17(3), 2012 (papers/000_…, line 188):
// §2.2 per-pixel rectification (line 247), §2.3 average distance (line 284), §2.4 layered
// rendering (line 303).
//
// Paper symbol ↔ variable (all vectors relative to the projection center c = map.camera.center):
//   x        reflector point                      xr = x − c
//   l̂        unit reflected direction             l
//   l1       current query vector                 l1 (world: c + l1 = EnvLookup::query)
//   D        initial search length                options.D
//   d_e      error tolerance                      options.d_e
//   N        step limit, eq. 1                    rectify_step_limit(D, d_e)
//   n        iteration count (1-based)            n
//   d, Δd    L_env(l1).a and d − |l1|             s.distance, delta
//   d_inf    empty texel                          kDistanceInf / CubeSample::empty
//   s, (m,n) sampling angle step and indices      step_rad, (m, k) in average_distance
//   d̄, K     average distance, valid samples      sum / count
//   l_rec    eq. 4 query vector                   xr + d_bar·l
//   L_1..L_M layers sorted near → far             layers[0 .. M−1]
#include "proxima/reflect/envmap_lookup.h"

#include <algorithm>
#include <cmath>

namespace proxima {

int rectify_step_limit(float D, float d_e) {
  return std::max(1, int(std::ceil(std::log2(2.0 * double(D) / double(d_e)))));
}

EnvLookup plain_lookup(const DistanceCubeMap& map, const Environment& env, vec3 dir) {
  EnvLookup r;
  CubeSample s = sample_cube(map, dir);
  r.steps = 1;
  r.query = map.camera.center + glm::normalize(dir);
  r.saw_inf = r.miss = s.empty;
  r.color = s.empty ? environment_radiance(env, dir) : s.color;
  r.object = s.object;
  return r;
}

EnvLookup rectified_lookup(const DistanceCubeMap& map, const Environment& env, vec3 x, vec3 dir,
                           const RectifyOptions& options) {
  const vec3 c = map.camera.center;
  const vec3 l = glm::normalize(dir);
  const int N = rectify_step_limit(options.D, options.d_e);
  EnvLookup r;
  vec3 l1 = (x - c) + options.D * l;
  float step = options.D;  // 2^(1−n)·D before the update of step n: halved each step (exact)
  for (int n = 1;; ++n) {
    const float d = sample_distance(map, l1);
    r.steps = n;
    r.saw_inf |= d == kDistanceInf;
    const float delta = d - glm::length(l1);  // +inf when empty: search farther
    if (std::abs(delta) < options.d_e) {
      r.converged = true;
      break;
    }
    if (n == N) break;
    step *= 0.5f;
    l1 += (delta > 0.0f ? step : -step) * l;
  }
  r.query = c + l1;
  if (!r.converged && r.saw_inf) {
    // Edge case (§2.2): the ray may pass beside the environment; the last lookup can lie
    // on a surface the ray never meets.
    r.miss = true;
    if (options.edge == EdgeRule::PlainFallback) {
      EnvLookup p = plain_lookup(map, env, l);
      r.color = p.color;
      r.object = p.object;
    }
    return r;
  }
  // The color at the final query (converged, or the bisection's last point within
  // 2^(1−N)·D when no lookup was d_inf).
  const CubeSample s = sample_cube(map, l1);
  r.color = s.empty ? environment_radiance(env, l) : s.color;
  r.miss = s.empty;
  r.object = s.object;
  return r;
}

float average_distance(const DistanceCubeMap& map, float step_rad) {
  // Paper axes (eq. 2, z up) → proxima's (+Y up): (cos ms·cos ns, sin ns, sin ms·cos ns).
  const int m_count = std::max(1, int(std::floor(2.0f * kPi / step_rad)));
  const int k_half = int(std::floor(0.5f * kPi / step_rad));
  double sum = 0.0;
  size_t count = 0;
  for (int k = -k_half; k <= k_half; ++k)
    for (int m = 0; m < m_count; ++m) {
      const float ms = float(m) * step_rad, ks = float(k) * step_rad;
      vec3 dir(std::cos(ms) * std::cos(ks), std::sin(ks), std::sin(ms) * std::cos(ks));
      CubeSample s = sample_cube(map, dir);
      if (s.empty) continue;
      sum += double(s.distance);
      ++count;
    }
  return count ? float(sum / double(count)) : kDistanceInf;
}

EnvLookup average_lookup(const DistanceCubeMap& map, const Environment& env, vec3 x, vec3 dir, float d_bar) {
  const vec3 l = glm::normalize(dir);
  if (d_bar == kDistanceInf) {  // an empty map: nothing to rectify against
    EnvLookup r;
    r.color = environment_radiance(env, l);
    r.saw_inf = r.miss = true;
    return r;
  }
  const vec3 l_rec = (x - map.camera.center) + d_bar * l;
  EnvLookup r = plain_lookup(map, env, l_rec);
  r.query = map.camera.center + l_rec;
  if (r.miss) r.color = environment_radiance(env, l);
  return r;
}

namespace {

// True when c is strictly in front of every triangle of the object: seen from c, the
// object shows only front faces and cannot hide another such object (for a room shell).
bool faces_center(const Scene& scene, uint32_t object, vec3 c) {
  const Object& o = scene.objects[object];
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
    const vec3 p0 = scene.positions[scene.triangles[t].x];
    if (glm::dot(triangle_normal(scene, t), c - p0) <= 0.0f) return false;
  }
  return o.triangle_count > 0;
}

}  // namespace

std::vector<EnvmapLayer> build_layers(const Scene& scene, const RayScene& rays, vec3 center,
                                      std::span<const uint32_t> exclude, const LayerOptions& options) {
  std::vector<std::vector<uint32_t>> groups;
  std::vector<uint32_t> enclosure;
  for (uint32_t o = 0; o < uint32_t(scene.objects.size()); ++o) {
    if (std::find(exclude.begin(), exclude.end(), o) != exclude.end()) continue;
    if (faces_center(scene, o, center))
      enclosure.push_back(o);
    else
      groups.push_back({o});
  }
  if (!enclosure.empty()) groups.push_back(enclosure);

  std::vector<EnvmapLayer> layers;
  for (const auto& group : groups) {
    EnvmapLayer layer;
    layer.objects = group;
    layer.enclosure = &group == &groups.back() && !enclosure.empty();
    DistanceCubeMapOptions mo = options.map;
    mo.objects = layer.objects;
    mo.exclude = {};
    layer.map = render_distance_cube_map(scene, rays, center, mo);
    if (layer.map.covered_fraction == 0.0) continue;  // nothing of it visible from c
    layer.average_distance = average_distance(layer.map, options.angle_step_rad);
    layer.per_pixel = layer.map.covered_fraction >= options.per_pixel_min_coverage;
    layers.push_back(std::move(layer));
  }
  // Near → far by d̄, the enclosure last; ties keep the grouping order (objects by id).
  std::stable_sort(layers.begin(), layers.end(), [](const EnvmapLayer& a, const EnvmapLayer& b) {
    if (a.enclosure != b.enclosure) return b.enclosure;
    return a.average_distance < b.average_distance;
  });
  return layers;
}

EnvLookup layered_lookup(std::span<const EnvmapLayer> layers, const Environment& env, vec3 x, vec3 dir,
                         const RectifyOptions& options) {
  RectifyOptions per_layer = options;
  per_layer.edge = EdgeRule::Black;  // a layer's edge case means "not in this layer"
  int steps = 0;
  for (const EnvmapLayer& layer : layers) {
    EnvLookup r = layer.per_pixel ? rectified_lookup(layer.map, env, x, dir, per_layer)
                                  : average_lookup(layer.map, env, x, dir, layer.average_distance);
    steps += r.steps;
    if (!r.miss) {
      r.steps = steps;
      return r;
    }
  }
  EnvLookup r;
  r.steps = steps;
  r.saw_inf = r.miss = true;
  if (options.edge == EdgeRule::PlainFallback) {
    r.color = environment_radiance(env, dir);
    for (const EnvmapLayer& layer : layers) {
      EnvLookup p = plain_lookup(layer.map, env, dir);
      if (!p.miss) {
        r.color = p.color;
        r.object = p.object;
        break;
      }
    }
  }
  return r;
}

}  // namespace proxima
