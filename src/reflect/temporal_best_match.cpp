// Algorithm 9 (thesis ch. 5 §5.4.1): local 3×3 descent on the match distance.
#include "proxima/reflect/temporal_best_match.h"

#include <algorithm>
#include <cmath>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// Only in optimized builds: the wide path relies on `flatten` inlining match_distance_lanes
// <Lanes16> and its lane ops into the avx512f code. Unoptimized (the Debug sanitizer build)
// the calls stay, and pass __m512 between a default-target and an avx512f function, whose
// ABIs differ: wrong distances (found by `make asan`). There the SSE2 path runs. GCC only:
// clang rejects the __m512 of the default-target template outright (the fuzz build).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__OPTIMIZE__)
#include <immintrin.h>
#define PROXIMA_BEST_MATCH_AVX512 1
// match_distance_lanes<Lanes16> passes __m512 in a default-target template; it is only ever
// inlined into the avx512f code, so no call with that ABI exists.
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#include "proxima/core/image_rgb.h"
#include "proxima/core/parallel.h"

namespace proxima {

namespace {

constexpr size_t kPixelGrain = 1024;  // reflective pixels per parallel chunk
// Squared distance below this fraction of its neighbours' counts as an exact match (the
// parabola would move it by < ~0.01 px).
constexpr float kExactMatch = 1e-4f;

// The 8-neighbourhood of a square in scan order (dy = −1..1, dx = −1..1, centre left out):
// the order of the descent's tie-breaks.
constexpr int kRing[8][2] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};

// match_distance, inlined into the descent: the start's chain of square roots and divisions
// then overlaps the first ring's.
inline __attribute__((always_inline)) float distance_to_mirrored_ray(vec3 w_n, vec3 n_n, vec3 reflected, vec3 eye) {
  const vec3 m = reflected - 2.0f * glm::dot(reflected - w_n, n_n) * n_n;
  const vec3 axis = w_n - m;
  const float len = glm::length(axis);
  if (!(len > 0.0f)) return glm::length(eye - w_n);
  const vec3 dir = axis / len;
  const vec3 e = eye - m;
  const float t = glm::dot(e, dir);
  return t <= 0.0f ? glm::length(e) : glm::length(e - t * dir);
}

struct Search {
  const ReflectionDepthImage& key;
  vec3 eye;
  int w, h;
  const float* position = key.position.data().data();
  const float* normal = key.normal.data().data();
  const uint32_t* objects = key.object.data().data();

  bool same(int x, int y, uint32_t object) const {
    return unsigned(x) < unsigned(w) && unsigned(y) < unsigned(h) &&
           objects[size_t(y) * size_t(w) + size_t(x)] == object;
  }
  float distance(int x, int y, vec3 r) const {
    return distance_to_mirrored_ray(rgb_at(key.position, x, y), rgb_at(key.normal, x, y), r, eye);
  }
  // match_distance of the 8 neighbours of (cx, cy) in kRing order; +inf for pixels of
  // another reflector (or none): outside the search space. The same operations as
  // match_distance lane by lane (IEEE single precision, no fused ops): the same bits.
  // Returns whether all 8 are on the reflector.
  bool ring(int cx, int cy, uint32_t object, vec3 r, float out[8]) const;
};

// match_distance on the lanes of L::V (lanes independent, each the exact sequence of
// match_distance: IEEE single precision, no fused ops): the same bits in any lane of any
// width. w, n: the candidates' W and s.n per coordinate.
template <class L>
inline __attribute__((always_inline)) typename L::V match_distance_lanes(const typename L::V w[3],
                                                                         const typename L::V n[3], vec3 r, vec3 eye) {
  using V = typename L::V;
  auto dot = [](V ax, V ay, V az, V bx, V by, V bz) {
    return L::add(L::add(L::mul(ax, bx), L::mul(ay, by)), L::mul(az, bz));
  };
  const V rx = L::set1(r.x), ry = L::set1(r.y), rz = L::set1(r.z);
  const V ex = L::set1(eye.x), ey = L::set1(eye.y), ez = L::set1(eye.z);
  // m = r − (2·dot(r − w, n))·n
  const V k = L::mul(L::set1(2.0f), dot(L::sub(rx, w[0]), L::sub(ry, w[1]), L::sub(rz, w[2]), n[0], n[1], n[2]));
  const V mx = L::sub(rx, L::mul(k, n[0])), my = L::sub(ry, L::mul(k, n[1])), mz = L::sub(rz, L::mul(k, n[2]));
  const V ax = L::sub(w[0], mx), ay = L::sub(w[1], my), az = L::sub(w[2], mz);
  const V len = L::sqrt(dot(ax, ay, az, ax, ay, az));
  const V dx = L::div(ax, len), dy = L::div(ay, len), dz = L::div(az, len);
  const V qx = L::sub(ex, mx), qy = L::sub(ey, my), qz = L::sub(ez, mz);
  const V t = dot(qx, qy, qz, dx, dy, dz);
  const V fx = L::sub(qx, L::mul(t, dx)), fy = L::sub(qy, L::mul(t, dy)), fz = L::sub(qz, L::mul(t, dz));
  // The cases pick the squared length, then one square root: a lane's sqrt is correctly
  // rounded, so the same bits as taking the root of each case and picking.
  const V d2 = L::if_le0(t, dot(qx, qy, qz, qx, qy, qz), dot(fx, fy, fz, fx, fy, fz));
  // Degenerate axis (len not > 0): the distance to W itself.
  const V gx = L::sub(ex, w[0]), gy = L::sub(ey, w[1]), gz = L::sub(ez, w[2]);
  return L::sqrt(L::if_gt0(len, d2, dot(gx, gy, gz, gx, gy, gz)));
}

#if defined(__SSE2__)
#define PROXIMA_SSE2 static inline __attribute__((always_inline))
struct Lanes4 {
  using V = __m128;
  PROXIMA_SSE2 V set1(float v) { return _mm_set1_ps(v); }
  PROXIMA_SSE2 V add(V a, V b) { return _mm_add_ps(a, b); }
  PROXIMA_SSE2 V sub(V a, V b) { return _mm_sub_ps(a, b); }
  PROXIMA_SSE2 V mul(V a, V b) { return _mm_mul_ps(a, b); }
  PROXIMA_SSE2 V div(V a, V b) { return _mm_div_ps(a, b); }
  PROXIMA_SSE2 V sqrt(V a) { return _mm_sqrt_ps(a); }
  PROXIMA_SSE2 V if_le0(V t, V a, V b) {  // t ≤ 0 ? a : b (NaN: b)
    const V m = _mm_cmple_ps(t, _mm_setzero_ps());
    return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b));
  }
  PROXIMA_SSE2 V if_gt0(V t, V a, V b) {  // t > 0 ? a : b (NaN: b)
    const V m = _mm_cmpgt_ps(t, _mm_setzero_ps());
    return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b));
  }
};
#undef PROXIMA_SSE2

// Four candidates at once. Inlined: a ring's two groups are independent chains the core
// then runs side by side.
inline __attribute__((always_inline)) __m128 match_distance4(const float* const w[4], const float* const n[4], vec3 r, vec3 eye) {
  const __m128 wv[3] = {_mm_setr_ps(w[0][0], w[1][0], w[2][0], w[3][0]), _mm_setr_ps(w[0][1], w[1][1], w[2][1], w[3][1]),
                        _mm_setr_ps(w[0][2], w[1][2], w[2][2], w[3][2])};
  const __m128 nv[3] = {_mm_setr_ps(n[0][0], n[1][0], n[2][0], n[3][0]), _mm_setr_ps(n[0][1], n[1][1], n[2][1], n[3][1]),
                        _mm_setr_ps(n[0][2], n[1][2], n[2][2], n[3][2])};
  return match_distance_lanes<Lanes4>(wv, nv, r, eye);
}
#endif

bool Search::ring(int cx, int cy, uint32_t object, vec3 r, float out[8]) const {
  bool in[8];
  const float* wp[8];
  const float* np[8];
  for (int k = 0; k < 8; ++k) {
    const int x = cx + kRing[k][0], y = cy + kRing[k][1];
    in[k] = same(x, y, object);
    const size_t i =
        in[k] ? (size_t(y) * size_t(w) + size_t(x)) * 3 : (size_t(cy) * size_t(w) + size_t(cx)) * 3;
    wp[k] = position + i;
    np[k] = normal + i;
  }
#if defined(__SSE2__)
  _mm_storeu_ps(out, match_distance4(wp, np, r, eye));
  _mm_storeu_ps(out + 4, match_distance4(wp + 4, np + 4, r, eye));
#else
  for (int k = 0; k < 8; ++k)
    out[k] = match_distance(vec3(wp[k][0], wp[k][1], wp[k][2]), vec3(np[k][0], np[k][1], np[k][2]), r, eye);
#endif
  bool all = true;
  for (int k = 0; k < 8; ++k)
    if (!in[k]) out[k] = kInf, all = false;
  return all;
}

#if defined(PROXIMA_BEST_MATCH_AVX512)
// The whole 3×3 square at once in one 16-lane AVX-512 group (runtime dispatch; the rest of
// the build stays SSE2): lane 4·row + column holds the cell (column − 1, row − 1) of the
// square, columns 0–2 and rows 0–2 (lanes 3, 7, 11, 12–15 are unused). Each row's 4 pixels
// (12 floats of the AoS position / normal) come in one masked load, so no cell outside the
// image is read, then are de-interleaved by two permutes per coordinate. Lane by lane the
// exact IEEE operations of match_distance (no fused ops: only avx512f is enabled here, and
// the build is ISO C++, -ffp-contract=off): the same bits as the SSE2 and scalar paths.
// The centre lane gives the start's distance with the first ring, off the walk's chain.
constexpr int kRingLane[8] = {0, 1, 2, 4, 6, 8, 9, 10};
constexpr int kCentreLane = 5;

// GCC 12 warns of its own _mm512_undefined_ps in the headers' sqrt (a false positive).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#define PROXIMA_AVX512 __attribute__((target("avx512f"))) inline __attribute__((always_inline))
// Not always_inline: match_distance_lanes (default target) calls these; they inline where
// it is inlined, in WideRing (flattened into walk_pixels_avx512).
#define PROXIMA_AVX512_OP static __attribute__((target("avx512f"))) inline
struct Lanes16 {
  using V = __m512;
  PROXIMA_AVX512_OP V set1(float v) { return _mm512_set1_ps(v); }
  PROXIMA_AVX512_OP V add(V a, V b) { return _mm512_add_ps(a, b); }
  PROXIMA_AVX512_OP V sub(V a, V b) { return _mm512_sub_ps(a, b); }
  PROXIMA_AVX512_OP V mul(V a, V b) { return _mm512_mul_ps(a, b); }
  PROXIMA_AVX512_OP V div(V a, V b) { return _mm512_div_ps(a, b); }
  PROXIMA_AVX512_OP V sqrt(V a) { return _mm512_sqrt_ps(a); }
  PROXIMA_AVX512_OP V if_le0(V t, V a, V b) {
    return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(t, _mm512_setzero_ps(), _CMP_LE_OQ), b, a);
  }
  PROXIMA_AVX512_OP V if_gt0(V t, V a, V b) {
    return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(t, _mm512_setzero_ps(), _CMP_GT_OQ), b, a);
  }
};
#undef PROXIMA_AVX512_OP
// De-interleave: coordinate k of lane 4·row + c is element 3c + k of row `row`.
PROXIMA_AVX512 __m512 coord16(const __m512 v[3], int k) {
  const __m512i i01 = _mm512_setr_epi32(k, 3 + k, 6 + k, 9 + k, 16 + k, 19 + k, 22 + k, 25 + k, 0, 0, 0, 0, 0, 0, 0, 0);
  const __m512 ab = _mm512_permutex2var_ps(v[0], i01, v[1]);
  const __m512i i2 = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 16 + k, 19 + k, 22 + k, 25 + k, 0, 0, 0, 0);
  return _mm512_permutex2var_ps(ab, i2, v[2]);
}

struct WideRing {
  const Search& s;
  __attribute__((target("avx512f"))) bool operator()(
      int cx, int cy, uint32_t object, vec3 r, float out[8], float* centre) const {
    const int w = s.w;
    // Columns cx − 1 .. cx + 2 inside the image (a 4-bit mask), rows cy − 1 .. cy + 1.
    const unsigned cols = 0x2u | (cx >= 1 ? 0x1u : 0u) | (cx + 1 < w ? 0x4u : 0u);
    const unsigned rows = 0x2u | (cy >= 1 ? 0x1u : 0u) | (cy + 1 < s.h ? 0x4u : 0u);
    // Per row: the 12 floats of columns cx − 1 .. cx + 2 (only the 3 of the mask used).
    auto float_mask = [&](unsigned c) {  // pixel mask → 12-float mask
      unsigned m = 0;
      for (int k = 0; k < 3; ++k)
        if (c & (1u << k)) m |= 0x7u << (3 * k);
      return __mmask16(m);
    };
    const __mmask16 fm = float_mask(cols);
    const ptrdiff_t base = ptrdiff_t(cy) * w + (cx - 1);  // pixel index of (cx − 1, cy)
    __m512i obj = _mm512_set1_epi32(int(kNoReflector));
    __m512 pr[3], nr[3];
    for (int row = 0; row < 3; ++row) {
      const bool ok = rows & (1u << row);
      const __mmask16 m = ok ? fm : __mmask16(0);
      const ptrdiff_t p = base + ptrdiff_t(row - 1) * w;  // may point before the image: masked
      pr[row] = _mm512_maskz_loadu_ps(m, s.position + 3 * p);
      nr[row] = _mm512_maskz_loadu_ps(m, s.normal + 3 * p);
      const __m512i o = _mm512_mask_loadu_epi32(_mm512_set1_epi32(int(kNoReflector)),
                                                ok ? __mmask16(cols) : __mmask16(0), s.objects + p);
      // this row's 4 ids into lanes 4·row .. 4·row + 3
      obj = _mm512_mask_permutexvar_epi32(obj, __mmask16(0xFu << (4 * row)),
                                          _mm512_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3), o);
    }
    const __mmask16 in = _mm512_cmpeq_epi32_mask(obj, _mm512_set1_epi32(int(object)));
    const __m512 wv[3] = {coord16(pr, 0), coord16(pr, 1), coord16(pr, 2)};
    const __m512 nv[3] = {coord16(nr, 0), coord16(nr, 1), coord16(nr, 2)};
    const __m512 d = match_distance_lanes<Lanes16>(wv, nv, r, s.eye);
    alignas(64) float lanes[16];
    _mm512_store_ps(lanes, _mm512_mask_blend_ps(in, _mm512_set1_ps(kInf), d));
    for (int k = 0; k < 8; ++k) out[k] = lanes[kRingLane[k]];
    if (centre) *centre = lanes[kCentreLane];
    return (in & 0x0757u) == 0x0757u;  // the 8 ring lanes (centre: on the reflector)
  }
};
#pragma GCC diagnostic pop
#endif

// std::lround for the offsets here (|v| < 2²²: pixel distances), without the library call:
// halves away from zero. v − trunc(v) is exact (Sterbenz), so the same integer.
int round_offset(float v) {
  const int t = int(v);
  const float f = v - float(t);
  return t + int(f >= 0.5f) - int(f <= -0.5f);
}

// Vertex of a parabola through (−1, a), (0, b), (1, c), clamped to ±0.5; 0 if not convex.
float parabola_vertex(float a, float b, float c) {
  const float denom = a - 2.0f * b + c;
  if (!(denom > 0.0f) || !std::isfinite(denom)) return 0.0f;
  return std::clamp(0.5f * (a - c) / denom, -0.5f, 0.5f);
}

// The walks of the key's reflective pixels j0 .. j1 − 1 (one parallel chunk).
struct Walk {
  const ReflectionDepthImage& key;
  const Search& s;
  const OffsetBuffer* previous;
  const OffsetBuffer* earlier;
  const BestMatchOptions& options;
  bool warm, extrapolate;
  int w, max_steps;
  float focal;
  vec2* offsets;
  uint8_t* valid;
};

// One pixel's walk, a step at a time, so the wide path can run two pixels' rings side by
// side (independent chains of square roots and divisions the core overlaps). Each pixel's
// steps are exactly the sequential walk's: the same bits whichever pixel runs beside it.
struct PixelWalk {
  size_t i;
  int x, y, cx, cy, step;
  uint32_t object;
  vec3 r;
  float former;
  bool need_former;  // the start's distance comes with the first ring (its centre lane)
  bool converged, inside;  // inside: the last ring was all on the reflector
  // The last step's 3×3 distances (centre included): on convergence they are the end
  // point's neighbours, which the sub-pixel fit reads again. Each step evaluates its
  // whole ring at once (SIMD): cells shared with the previous square get the same bits.
  float around[3][3];
};

struct Walker {
  const Walk& c;
  size_t row;  // key.pixels is row-major ascending: follow the row instead of dividing per pixel
  int y;
  uint64_t steps = 0, invalid = 0;

  Walker(const Walk& walk, size_t j0, size_t j1) : c(walk) {
    y = j0 < j1 ? int(c.key.pixels[j0] / size_t(c.w)) : 0;
    row = size_t(y) * size_t(c.w);
  }

  // The start of pixel j's walk: s + the previous offset (or the extrapolated guess).
  void begin(PixelWalk& p, size_t j, bool centre_from_ring) {
    const Search& s = c.s;
    const size_t i = c.key.pixels[j];
    while (i >= row + size_t(c.w)) ++y, row += size_t(c.w);
    p.i = i;
    p.x = int(i - row);
    p.y = y;
    p.object = s.objects[i];
    p.r = c.key.reflected[j];
    p.cx = p.x, p.cy = p.y;
    if (c.warm) {  // INVALID pixels too: their end point saves the next walk
      const vec2 o = c.previous->offset[i];
      const int px = p.x + round_offset(o.x), py = p.y + round_offset(o.y);
      if (s.same(px, py, p.object)) p.cx = px, p.cy = py;
    }
    p.need_former = centre_from_ring && !c.extrapolate;
    p.former = p.need_former ? 0.0f : s.distance(p.cx, p.cy, p.r);
    if (c.extrapolate) {  // steady motion: the offset moves on by its last change
      const vec2 guess = 2.0f * c.previous->offset[i] - c.earlier->offset[i];
      const int gx = p.x + round_offset(guess.x), gy = p.y + round_offset(guess.y);
      if ((gx != p.cx || gy != p.cy) && s.same(gx, gy, p.object)) {
        const float d = s.distance(gx, gy, p.r);
        if (d < p.former) p.former = d, p.cx = gx, p.cy = gy;
      }
    }
    p.step = 0;
    p.converged = false;
    p.inside = true;
    for (auto& a : p.around) a[0] = a[1] = a[2] = 0.0f;
  }

  // One descent step from the ring of (cx, cy): whether the walk has ended.
  bool advance(PixelWalk& p, bool inside, const float d8[8], float centre) {
    if (p.need_former) p.former = centre, p.need_former = false;
    p.inside = inside;
    int bx = p.cx, by = p.cy;
    float best = kInf;
    for (int k = 0; k < 8; ++k) {
      p.around[kRing[k][1] + 1][kRing[k][0] + 1] = d8[k];
      if (d8[k] < best) best = d8[k], bx = p.cx + kRing[k][0], by = p.cy + kRing[k][1];
    }
    p.around[1][1] = p.former;
    if (!(best < p.former)) {  // local minimum (ties stop too: no cycles)
      p.converged = true;
      return true;
    }
    p.former = best;
    p.cx = bx;
    p.cy = by;
    ++steps;
    return ++p.step >= c.max_steps;
  }

  void finish(const PixelWalk& p) {
    const ReflectionDepthImage& key = c.key;
    const int cx = p.cx, cy = p.cy;
    const float former = p.former;
    bool ok = p.converged;
    if (ok) {
      // On the silhouette border the true minimum may lie outside the reflector: keep
      // the match only if the reflected ray through W_c misses E_cur by ≤ tolerance
      // key pixels (distance scaled back to W_c by similar triangles).
      // (the end point's 3×3 is on the reflector but for the ring's cells outside)
      if (!p.inside) {
        const vec3 r = p.r;
        const vec3 wc = rgb_at(key.position, cx, cy), nc = rgb_at(key.normal, cx, cy);
        const vec3 m = r - 2.0f * glm::dot(r - wc, nc) * nc;
        const float scale = glm::length(wc - m) / std::max(glm::length(c.s.eye - m), 1e-6f);
        const float miss_px = former * scale * c.focal / std::max(key.depth.at(cx, cy), 1e-6f);
        ok = miss_px <= c.options.border_tolerance_px;
      }
    }
    if (!ok) {
      ++invalid;
      c.offsets[p.i] = vec2(float(cx - p.x), float(cy - p.y));
      c.valid[p.i] = 0;
      return;
    }
    vec2 sub(0.0f);
    if (c.options.subpixel) {
      auto sq = [&](int dx, int dy) { return p.around[dy + 1][dx + 1] * p.around[dy + 1][dx + 1]; };
      const float b = former * former;
      const float l = sq(-1, 0), rr = sq(1, 0), u = sq(0, -1), dn = sq(0, 1);
      // An (almost) exact match stays put: near a zero of the distance its square is
      // far from a parabola where the reflection is close (small s.r).
      auto exact = [&](float a, float q) { return b <= kExactMatch * std::min(a, q); };
      if (std::isfinite(l) && std::isfinite(rr) && !exact(l, rr)) sub.x = parabola_vertex(l, b, rr);
      if (std::isfinite(u) && std::isfinite(dn) && !exact(u, dn)) sub.y = parabola_vertex(u, b, dn);
    }
    c.offsets[p.i] = vec2(float(cx - p.x), float(cy - p.y)) + sub;
    c.valid[p.i] = 1;
  }
};

void walk_pixels_sse(const Walk& c, size_t j0, size_t j1, uint64_t& steps, uint64_t& invalid) {
  Walker walker(c, j0, j1);
  PixelWalk p;
  for (size_t j = j0; j < j1; ++j) {
    walker.begin(p, j, false);
    for (;;) {
      float d8[8];
      const bool inside = c.s.ring(p.cx, p.cy, p.object, p.r, d8);
      if (walker.advance(p, inside, d8, 0.0f)) break;
    }
    walker.finish(p);
  }
  steps = walker.steps;
  invalid = walker.invalid;
}

#if defined(PROXIMA_BEST_MATCH_AVX512)
// Two pixels' walks side by side, each refilled from j0 .. j1 − 1 in order as it ends.
// flatten: the Walker and WideRing inline here, in the avx512f context.
__attribute__((target("avx512f"), flatten)) void walk_pixels_avx512(const Walk& c, size_t j0, size_t j1,
                                                                      uint64_t& steps, uint64_t& invalid) {
  Walker walker(c, j0, j1);
  const WideRing ring{c.s};
  PixelWalk p[2];
  size_t next = j0;
  bool live[2];
  for (int k = 0; k < 2; ++k)
    if ((live[k] = next < j1)) walker.begin(p[k], next++, true);
  while (live[0] || live[1]) {
    float d8[2][8], centre[2] = {0.0f, 0.0f};
    bool inside[2] = {true, true};
    for (int k = 0; k < 2; ++k)
      if (live[k]) inside[k] = ring(p[k].cx, p[k].cy, p[k].object, p[k].r, d8[k], &centre[k]);
    for (int k = 0; k < 2; ++k)
      if (live[k] && walker.advance(p[k], inside[k], d8[k], centre[k])) {
        walker.finish(p[k]);
        if ((live[k] = next < j1)) walker.begin(p[k], next++, true);
      }
  }
  steps = walker.steps;
  invalid = walker.invalid;
}
bool has_avx512() {
  static const bool yes = __builtin_cpu_supports("avx512f");
  return yes;
}
#endif

}  // namespace

namespace detail {
bool best_match_wide = true;
bool best_match_wide_available() {
#if defined(PROXIMA_BEST_MATCH_AVX512)
  return has_avx512();
#else
  return false;
#endif
}
}  // namespace detail

namespace {
}  // namespace

float match_distance(vec3 w_n, vec3 n_n, vec3 reflected, vec3 eye) {
  return distance_to_mirrored_ray(w_n, n_n, reflected, eye);
}

OffsetBuffer best_match_search(const ReflectionDepthImage& key, vec3 eye, const OffsetBuffer* previous,
                               const BestMatchOptions& options, BestMatchStats* stats,
                               const OffsetBuffer* earlier) {
  OffsetBuffer out;  // fresh: zero, as the contract says, where no pixel is written
  best_match_search_into(key, eye, previous, options, out, stats, earlier);
  return out;
}

void best_match_search_into(const ReflectionDepthImage& key, vec3 eye, const OffsetBuffer* previous,
                            const BestMatchOptions& options, OffsetBuffer& out, BestMatchStats* stats,
                            const OffsetBuffer* earlier) {
  const int w = key.object.width(), h = key.object.height();
  if (out.width != w || out.height != h || out.offset.size() != size_t(w) * size_t(h)) {
    out.width = w;
    out.height = h;
    out.offset.assign(size_t(w) * size_t(h), vec2(0.0f));
    out.valid.assign(size_t(w) * size_t(h), 0);
  }
  const bool warm = previous && previous->width == w && previous->height == h;
  const bool extrapolate =
      warm && options.extrapolate && earlier && earlier->width == w && earlier->height == h;
  const int max_steps = options.max_steps > 0 ? options.max_steps : w + h;
  const float focal = focal_length_px(key.camera);
  const Search s{key, eye, w, h};
  // The key's reflective pixels and their R (make_reflection_depth_image), in fixed chunks.
  const size_t n = key.pixels.size();
  const size_t chunks = (n + kPixelGrain - 1) / kPixelGrain;
  std::vector<uint64_t> chunk_steps(chunks, 0), chunk_invalid(chunks, 0);
  vec2* const offsets = out.offset.data();
  uint8_t* const valid = out.valid.data();

  const Walk walk{key, s, previous, earlier, options, warm, extrapolate, w, max_steps, focal, offsets, valid};
#if defined(PROXIMA_BEST_MATCH_AVX512)
  const bool wide = detail::best_match_wide && has_avx512();
#endif
  parallel_for(n, kPixelGrain, [&](size_t j0, size_t j1) {
    const size_t chunk = j0 / kPixelGrain;
    uint64_t steps = 0, invalid = 0;
#if defined(PROXIMA_BEST_MATCH_AVX512)
    if (wide)
      walk_pixels_avx512(walk, j0, j1, steps, invalid);
    else
#endif
      walk_pixels_sse(walk, j0, j1, steps, invalid);
    chunk_steps[chunk] = steps;
    chunk_invalid[chunk] = invalid;
  });
  if (stats) {
    *stats = {};
    stats->searched = n;
    for (size_t c = 0; c < chunks; ++c) {
      stats->invalid += chunk_invalid[c];
      stats->steps += chunk_steps[c];
    }
  }
}

}  // namespace proxima
