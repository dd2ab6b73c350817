// Environment-map lookups along a reflected ray (Wang et al. 2012, §2.2–2.3): plain
// (direction only), per-pixel rectification by bisection on the distance map, average-
// distance rectification; and a ray march over a depth-peeled layered distance map
// (Szirmay-Kalos et al.'s layered distance maps) in place of the paper's §2.4.
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
  // Layered lookups only:
  int max_march_steps = 64;  // ray-march samples per lookup at most (about 2 texels apart)
  float edge_jump = 0.02f;   // relative spread of a filter's tap distances that marks a silhouette
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
  int layer = 0;                  // layered: the layer the color came from
  bool fallback = false;          // layered: no hit found, the rectified lookup on layer 0 used
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

// Layered lookup over `layers` (render_distance_cube_layers: layer 0 the ordinary map,
// layer k the surfaces behind layer k − 1 as seen from c). The ray x + t·l̂ is marched
// over t ∈ [t0, 2D] (t0: where |l1| first reaches the nearest distance of layer 0) in
// steps about two texels apart as seen from c, at most max_march_steps; at each sample it
// is behind layers 0 … n − 1 (d_k < |l1|) and in front of layer n. Where n grows between
// samples the ray crossed layer n's surface or passed behind one of its silhouettes:
// bisection on Δd_n = d_n − |l1| in that interval. A root |Δd_n| < d_e is a hit — the
// nearest along the ray, its layer's color — when its filter taps lie on one surface: one
// object, or spread ≤ edge_jump, or two objects whose distances continue each other
// (cube_taps_continuous: a seam or crease seen at a grazing angle; then the color of the
// object whose own surface passes nearest, not a blend). Across a step between two
// objects the point is still a hit on one of them when it lies within that object's own
// tap distances, or where a bisection on that object's distance alone finds the ray went
// through it before the blended root. Otherwise it is a silhouette, and the next layer is
// searched in the same interval. Where layer n's distance jumps from near to far between samples, the near
// side of the silhouette is checked for a crossing too. A ray that ends in front of every
// layer escapes (environment radiance, miss); one that ends behind a layer without a hit
// (its surface is deeper than the layers, unreachable, or between two samples) takes the
// §2.2 rectified lookup on layer 0 (fallback = true). Deterministic; thread-safe.
EnvLookup layered_lookup(std::span<const DistanceCubeMap> layers, const Environment& env, vec3 x, vec3 dir,
                         const RectifyOptions& options);

}  // namespace proxima
