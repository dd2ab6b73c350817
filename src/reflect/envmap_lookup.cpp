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
//   (layered) layer k of the peeled map           layers[k]; n = layers the ray is behind
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

// The ray x + t·l̂ relative to c, and its layers' distances along it.
struct LayeredRay {
  std::span<const DistanceCubeMap> layers;
  vec3 xr, l;
  int samples = 0;

  vec3 at(float t) const { return xr + t * l; }
  // d_k at t (+inf where layer k is empty there); *rho = |l1|.
  float distance(int k, float t, float* rho) {
    ++samples;
    const vec3 q = at(t);
    *rho = glm::length(q);
    return sample_distance(layers[size_t(k)], q);
  }
  // Δd_k = d_k − |l1| at t (+inf where layer k is empty there).
  float delta(int k, float t) {
    float rho = 0.0f;
    const float d = distance(k, t, &rho);
    return d - rho;
  }
  // n: the ray at t is behind layers 0 … n − 1 and in front of layer n, whose distance
  // goes to *front (+inf when n = K).
  int behind(float t, float* front) {
    int n = 0;
    *front = kDistanceInf;
    for (; n < int(layers.size()); ++n) {
      float rho = 0.0f;
      const float d = distance(n, t, &rho);
      if (!(d < rho)) {
        *front = d;
        break;
      }
    }
    return n;
  }
};

// Two distances of one layer on different surfaces (a silhouette between them).
bool jump(float a, float b, float edge_jump) {
  if (a == kDistanceInf || b == kDistanceInf) return a != b;
  return std::abs(a - b) > edge_jump * std::min(a, b);
}

}  // namespace

EnvLookup layered_lookup(std::span<const DistanceCubeMap> layers, const Environment& env, vec3 x, vec3 dir,
                         const RectifyOptions& options) {
  EnvLookup r;
  const vec3 l = glm::normalize(dir);
  if (layers.empty()) {
    r.color = environment_radiance(env, l);
    r.saw_inf = r.miss = true;
    return r;
  }
  const DistanceCubeMap& base = layers[0];
  const vec3 c = base.camera.center;
  LayeredRay ray{layers, x - c, l};
  // The march starts at t_lo, where the ray is first as far from c as the nearest surface
  // of layer 0 (every deeper layer lies behind it): before that it is in front of everything.
  const float t_hi = 2.0f * options.D;
  const float near = 0.999f * base.min_distance;
  const float xl = glm::dot(ray.xr, l), xx = glm::dot(ray.xr, ray.xr);
  const float t_lo = xx < near * near ? -xl + std::sqrt(std::max(0.0f, xl * xl - xx + near * near)) : 0.0f;
  if (!(t_lo < t_hi)) {  // an empty map, or nothing within reach
    r.color = environment_radiance(env, l);
    r.query = c + ray.at(t_hi);
    r.saw_inf = r.miss = true;
    return r;
  }
  const vec3 v0 = ray.at(t_lo);
  const float len0 = std::max(glm::length(v0), 1e-6f * options.D);
  const float len1 = glm::length(ray.at(t_hi));
  const float arc = std::acos(std::clamp(glm::dot(v0 / len0, ray.at(t_hi) / len1), -1.0f, 1.0f));
  const float texel = 2.0f / float(base.camera.resolution);  // angle of a texel at a face centre
  const int steps = std::clamp(int(std::ceil(arc / (2.0f * texel))), 1, std::max(1, options.max_march_steps));
  // Samples t(s), s = i/S: the direction from c moves linearly along the chord between
  // the directions of the ray at t_lo and at its end t_hi = 2D, so samples are about equally
  // far apart in the map, about two texels (a radial ray: one interval).
  auto t_of = [&](int i) {
    if (i >= steps) return t_hi;
    const float s = float(i) / float(steps);
    return t_lo + (t_hi - t_lo) * (s / len1) / ((1.0f - s) / len0 + s / len1);
  };
  const float min_width = 0.05f * options.d_e;
  // Whether the ray meets layer m's surface at t, a root of the filtered Δd_m (|Δd_m| < d_e)
  // bracketed from a (in front of layer m): the sample to show and the hit's t.
  auto surface_hit = [&](int m, float a, float t, CubeSample* out, float* t_hit) {
    const DistanceCubeMap& layer = layers[size_t(m)];
    const vec3 q = ray.at(t);
    const float rho = glm::length(q);
    const CubeSample s = sample_cube(layer, q);
    ++ray.samples;
    if (s.empty) return false;
    *t_hit = t;
    const float tol = options.edge_jump * s.tap_min + options.d_e;
    if (s.one_object || s.tap_max - s.tap_min <= tol) {  // the taps on one surface
      *out = s;
      return true;
    }
    // The taps show two objects. Of them, the one whose own surface passes nearest the point.
    const CubeSample own = sample_cube_surface(layer, q, rho);
    ray.samples += 2;
    if (own.empty) return false;
    // One continuous surface across them (a seam or a crease seen at a grazing angle, where
    // neighbouring texels differ by more than edge_jump): a hit, with that object's color
    // rather than a blend of two materials.
    if (cube_taps_continuous(layer, q, tol)) {
      *out = own;
      return true;
    }
    // A step between them (a silhouette): the point may still lie on that object, within
    // its taps' distances ...
    if (rho > own.tap_min - options.d_e && rho < own.tap_max + options.d_e) {
      *out = own;
      return true;
    }
    // ... or the ray went through that object's surface before the blended ramp's root:
    // bisection on its distance alone (where it covers half the filter) over [a, t].
    if (!(own.distance < rho)) return false;
    float lo = a, hi = t;
    while (hi - lo > min_width) {
      const float mid = 0.5f * (lo + hi);
      const vec3 p = ray.at(mid);
      const CubeSample so = sample_cube_object(layer, p, own.object);
      ++ray.samples;
      const float delta = so.empty ? kDistanceInf : so.distance - glm::length(p);
      if (std::abs(delta) < options.d_e) {
        *out = so;
        *t_hit = mid;
        return true;
      }
      (delta > 0.0f ? lo : hi) = mid;
    }
    return false;
  };
  // Bisection on Δd_m over [*a, b] (in front of layer m at *a, behind it at b). A root that
  // surface_hit accepts is a hit (written to r); otherwise (no root, or a filtered ramp
  // across a silhouette) the ray passed behind a silhouette of layer m and *a moves to the
  // last point in front.
  auto refine = [&](int m, float* a, float b) {
    float lo = *a, hi = b;
    while (hi - lo > min_width) {
      const float mid = 0.5f * (lo + hi);
      const float delta = ray.delta(m, mid);
      if (std::abs(delta) < options.d_e) {
        CubeSample s;
        float t_hit = mid;
        if (surface_hit(m, *a, mid, &s, &t_hit)) {
          r.color = s.color;
          r.object = s.object;
          r.query = c + ray.at(t_hit);
          r.converged = true;
          r.layer = m;
          return true;
        }
        break;  // a filtered ramp across a silhouette, not a surface
      }
      (delta > 0.0f ? lo : hi) = mid;
    }
    *a = lo;
    return false;
  };
  int n_prev = 0;  // x lies in front of every layer (nothing of the environment inside the reflector)
  float t_prev = t_lo;
  float front_prev = kDistanceInf;
  if (ray.behind(t_lo, &front_prev) != 0) front_prev = kDistanceInf;
  for (int i = 1; i <= steps; ++i) {
    const float t = t_of(i);
    float front = kDistanceInf;
    const int n = ray.behind(t, &front);
    float a = t_prev;
    for (int m = n_prev; m < n; ++m) {
      // In front of layer m at a, behind it at t: a surface crossing or a silhouette.
      if (refine(m, &a, t)) {
        r.steps = ray.samples;
        return r;
      }
    }
    if (n == n_prev && n < int(layers.size()) && front_prev < front && jump(front_prev, front, options.edge_jump)) {
      // In front of layer n at both ends, the near surface at t_prev's side, a farther one
      // (or none) at t's: the ray may have gone through the near surface just before its
      // silhouette. Find the silhouette, and look for Δd < 0 on its near side.
      float lo = t_prev, hi = t;
      for (int k = 0; k < 24 && hi - lo > min_width; ++k) {
        const float mid = 0.5f * (lo + hi);
        float rho = 0.0f;
        const float d = ray.distance(n, mid, &rho);
        if (d < rho) {  // behind the near surface already: a crossing in [t_prev, mid]
          hi = mid;
          float a2 = t_prev;
          if (refine(n, &a2, hi)) {
            r.steps = ray.samples;
            return r;
          }
          break;
        }
        (jump(front_prev, d, options.edge_jump) ? hi : lo) = mid;
      }
    }
    n_prev = n;
    t_prev = t;
    front_prev = front;
  }
  if (n_prev == 0) {
    // In front of every layer at t_hi: the ray leaves the environment.
    r.color = environment_radiance(env, l);
    r.query = c + ray.at(t_hi);
    r.saw_inf = r.miss = true;
    r.steps = ray.samples;
    return r;
  }
  EnvLookup f = rectified_lookup(base, env, x, dir, options);
  f.steps += ray.samples;
  f.fallback = true;
  return f;
}

}  // namespace proxima
