// Environment-map lookups along a reflected ray (Wang et al. 2012, §2.2–2.4): plain
// (direction only), per-pixel rectification by bisection on the distance map, average-
// distance rectification, and layered lookups over one map per environment object.
// Points are world space; the map's projection center c plays the paper's origin.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/reflect/distance_cube_map.h"
#include "proxima/scene/light.h"

namespace proxima {

// What a rectified search that ends by step count after a d_inf lookup outputs (§2.2).
enum class EdgeRule {
  Black,          // the paper: output 0 (the reflected ray is taken to miss the environment)
  PlainFallback,  // the plain direction lookup instead (no black seams; may show the wrong surface)
};

struct RectifyOptions {
  float D = 12.0f;    // search length (m): the hit must lie within [x, x + 2D·l̂) (paper: 12)
  float d_e = 0.01f;  // tolerance d_e (m) on |d − |l1||, and the bisection's resolution
  EdgeRule edge = EdgeRule::Black;
};

// N = ⌈log2(2D/d_e)⌉ (eq. 1, rounded up so the last step is ≤ d_e), at least 1.
int rectify_step_limit(float D, float d_e);

struct EnvLookup {
  vec3 color{0.0f};               // radiance returned
  vec3 query{0.0f};               // world point c + l1 of the last map lookup
  int steps = 0;                  // map lookups made (≤ N for the rectified search)
  bool converged = false;         // ended by condition 1, |Δd| < d_e
  bool saw_inf = false;           // some lookup returned d_inf
  bool miss = false;              // nothing found: the edge rule applied, or the lookup was d_inf
  uint32_t object = 0xFFFFFFFFu;  // object the color came from (kNoObject: environment/black)
};

// Plain environment mapping: the texel along `dir` from c; environment_radiance(dir) where
// the map is empty (miss = true).
EnvLookup plain_lookup(const DistanceCubeMap& map, const Environment& env, vec3 dir);

// §2.2 bisection along the ray x + t·l̂ (l̂ = normalize(dir)): l1 = x + D·l̂ (relative to
// c); per step d = L_env(l1).a, Δd = d − |l1|; stop when |Δd| < d_e (condition 1) or
// n = N (condition 2), else l1 += sgn(Δd)·2^−n·D·l̂. Ending by condition 2 after a d_inf
// lookup is the edge case: black, or the plain lookup (options.edge); miss = true.
EnvLookup rectified_lookup(const DistanceCubeMap& map, const Environment& env, vec3 x, vec3 dir,
                           const RectifyOptions& options);

// §2.3 d̄ (eqs. 2–3): the mean distance over the non-d_inf samples of the directions
// (cos ms·cos ns, sin ms·cos ns, sin ns) with angle step s = step_rad, m·s ∈ [0, 2π),
// n·s ∈ [−π/2, π/2] (paper's axes, z up: equal-angle, not equal-area). kDistanceInf when
// no sample hits. step_rad in (0, π/2].
float average_distance(const DistanceCubeMap& map, float step_rad);

// §2.3 eq. 4: the lookup along l_rec = x + d̄·l̂ (relative to c); environment where empty.
EnvLookup average_lookup(const DistanceCubeMap& map, const Environment& env, vec3 x, vec3 dir, float d_bar);

// §2.4: one map per environment object.
struct EnvmapLayer {
  DistanceCubeMap map;
  std::vector<uint32_t> objects;          // the objects drawn into it
  float average_distance = kDistanceInf;  // d̄ of the layer (eq. 3): its sort key
  bool per_pixel = true;                  // rectified by bisection; false: by d̄ (small solid angle)
  bool enclosure = false;                 // the objects facing c (sorted last)
};

struct LayerOptions {
  DistanceCubeMapOptions map;            // resolution, light samples, seed (objects/exclude unused)
  float angle_step_rad = 0.0349066f;     // s of eq. 2 (2°)
  double per_pixel_min_coverage = 0.05;  // a layer covering less of the cube uses d̄
};

// Layers around `center` for every object not in `exclude`: the enclosure — objects whose
// every triangle faces c (walls, floor, ceiling, lamps on them; they cannot occlude each
// other as seen from c) — is one layer, every other object is a layer of its own. Sorted
// near → far by d̄, the enclosure last: it surrounds c, so everything else lies in front of
// it (its d̄ can be smaller than that of furniture standing at its walls).
std::vector<EnvmapLayer> build_layers(const Scene& scene, const RayScene& rays, vec3 center,
                                      std::span<const uint32_t> exclude, const LayerOptions& options);

// §2.4: the first layer (near → far) whose rectified lookup (per_pixel: bisection;
// otherwise d̄) is not a miss gives the color. When every layer misses: black, or with
// PlainFallback the first layer's non-empty plain lookup (else the environment).
EnvLookup layered_lookup(std::span<const EnvmapLayer> layers, const Environment& env, vec3 x, vec3 dir,
                         const RectifyOptions& options);

}  // namespace proxima
