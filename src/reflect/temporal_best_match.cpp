// Algorithm 9 (thesis ch. 5 §5.4.1): local 3×3 descent on the match distance.
#include "proxima/reflect/temporal_best_match.h"

#include <algorithm>
#include <cmath>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define PROXIMA_BEST_MATCH_AVX512 1
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

#if defined(__SSE2__)
// Four candidates at once; lanes are independent, each the exact sequence of match_distance.
// Inlined: a ring's two groups are independent chains the core then runs side by side.
inline __attribute__((always_inline)) __m128 match_distance4(const float* const w[4], const float* const n[4], vec3 r, vec3 eye) {
  const __m128 wx = _mm_setr_ps(w[0][0], w[1][0], w[2][0], w[3][0]);
  const __m128 wy = _mm_setr_ps(w[0][1], w[1][1], w[2][1], w[3][1]);
  const __m128 wz = _mm_setr_ps(w[0][2], w[1][2], w[2][2], w[3][2]);
  const __m128 nx = _mm_setr_ps(n[0][0], n[1][0], n[2][0], n[3][0]);
  const __m128 ny = _mm_setr_ps(n[0][1], n[1][1], n[2][1], n[3][1]);
  const __m128 nz = _mm_setr_ps(n[0][2], n[1][2], n[2][2], n[3][2]);
  const __m128 rx = _mm_set1_ps(r.x), ry = _mm_set1_ps(r.y), rz = _mm_set1_ps(r.z);
  const __m128 ex = _mm_set1_ps(eye.x), ey = _mm_set1_ps(eye.y), ez = _mm_set1_ps(eye.z);
  auto dot = [](__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
  };
  // m = r − (2·dot(r − w, n))·n
  const __m128 k = _mm_mul_ps(_mm_set1_ps(2.0f),
                              dot(_mm_sub_ps(rx, wx), _mm_sub_ps(ry, wy), _mm_sub_ps(rz, wz), nx, ny, nz));
  const __m128 mx = _mm_sub_ps(rx, _mm_mul_ps(k, nx)), my = _mm_sub_ps(ry, _mm_mul_ps(k, ny)),
               mz = _mm_sub_ps(rz, _mm_mul_ps(k, nz));
  const __m128 ax = _mm_sub_ps(wx, mx), ay = _mm_sub_ps(wy, my), az = _mm_sub_ps(wz, mz);
  const __m128 len = _mm_sqrt_ps(dot(ax, ay, az, ax, ay, az));
  const __m128 dx = _mm_div_ps(ax, len), dy = _mm_div_ps(ay, len), dz = _mm_div_ps(az, len);
  const __m128 qx = _mm_sub_ps(ex, mx), qy = _mm_sub_ps(ey, my), qz = _mm_sub_ps(ez, mz);
  const __m128 t = dot(qx, qy, qz, dx, dy, dz);
  const __m128 fx = _mm_sub_ps(qx, _mm_mul_ps(t, dx)), fy = _mm_sub_ps(qy, _mm_mul_ps(t, dy)),
               fz = _mm_sub_ps(qz, _mm_mul_ps(t, dz));
  // The cases pick the squared length, then one square root: a lane's sqrt is correctly
  // rounded, so the same bits as taking the root of each case and picking.
  const __m128 behind = _mm_cmple_ps(t, _mm_setzero_ps());
  const __m128 d2 = _mm_or_ps(_mm_and_ps(behind, dot(qx, qy, qz, qx, qy, qz)),
                              _mm_andnot_ps(behind, dot(fx, fy, fz, fx, fy, fz)));
  // Degenerate axis (len not > 0): the distance to W itself.
  const __m128 gx = _mm_sub_ps(ex, wx), gy = _mm_sub_ps(ey, wy), gz = _mm_sub_ps(ez, wz);
  const __m128 ok = _mm_cmpgt_ps(len, _mm_setzero_ps());
  return _mm_sqrt_ps(_mm_or_ps(_mm_and_ps(ok, d2), _mm_andnot_ps(ok, dot(gx, gy, gz, gx, gy, gz))));
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
PROXIMA_AVX512 __m512 dot16(__m512 ax, __m512 ay, __m512 az, __m512 bx, __m512 by, __m512 bz) {
  return _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(ax, bx), _mm512_mul_ps(ay, by)), _mm512_mul_ps(az, bz));
}
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
    unsigned cols = 0x2u | (cx >= 1 ? 0x1u : 0u) | (cx + 1 < w ? 0x4u : 0u);
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
    const __m512 zero = _mm512_setzero_ps();
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
    const __m512 wx = coord16(pr, 0), wy = coord16(pr, 1), wz = coord16(pr, 2);
    const __m512 nx = coord16(nr, 0), ny = coord16(nr, 1), nz = coord16(nr, 2);
    const __m512 rx = _mm512_set1_ps(r.x), ry = _mm512_set1_ps(r.y), rz = _mm512_set1_ps(r.z);
    const __m512 ex = _mm512_set1_ps(s.eye.x), ey = _mm512_set1_ps(s.eye.y), ez = _mm512_set1_ps(s.eye.z);
    const __m512 k2 = _mm512_mul_ps(
        _mm512_set1_ps(2.0f), dot16(_mm512_sub_ps(rx, wx), _mm512_sub_ps(ry, wy), _mm512_sub_ps(rz, wz), nx, ny, nz));
    const __m512 mx = _mm512_sub_ps(rx, _mm512_mul_ps(k2, nx)), my = _mm512_sub_ps(ry, _mm512_mul_ps(k2, ny)),
                 mz = _mm512_sub_ps(rz, _mm512_mul_ps(k2, nz));
    const __m512 ax = _mm512_sub_ps(wx, mx), ay = _mm512_sub_ps(wy, my), az = _mm512_sub_ps(wz, mz);
    const __m512 len = _mm512_sqrt_ps(dot16(ax, ay, az, ax, ay, az));
    const __m512 dx = _mm512_div_ps(ax, len), dy = _mm512_div_ps(ay, len), dz = _mm512_div_ps(az, len);
    const __m512 qx = _mm512_sub_ps(ex, mx), qy = _mm512_sub_ps(ey, my), qz = _mm512_sub_ps(ez, mz);
    const __m512 t = dot16(qx, qy, qz, dx, dy, dz);
    const __m512 fx = _mm512_sub_ps(qx, _mm512_mul_ps(t, dx)), fy = _mm512_sub_ps(qy, _mm512_mul_ps(t, dy)),
                 fz = _mm512_sub_ps(qz, _mm512_mul_ps(t, dz));
    const __mmask16 behind = _mm512_cmp_ps_mask(t, zero, _CMP_LE_OQ);
    const __m512 d2 = _mm512_mask_blend_ps(behind, dot16(fx, fy, fz, fx, fy, fz), dot16(qx, qy, qz, qx, qy, qz));
    const __m512 gx = _mm512_sub_ps(ex, wx), gy = _mm512_sub_ps(ey, wy), gz = _mm512_sub_ps(ez, wz);
    const __mmask16 okl = _mm512_cmp_ps_mask(len, zero, _CMP_GT_OQ);
    const __m512 d = _mm512_sqrt_ps(_mm512_mask_blend_ps(okl, dot16(gx, gy, gz, gx, gy, gz), d2));
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

// The walks of the key's reflective pixels j0 .. j1 − 1 (one parallel chunk). `ring` is
// WideRing for kWide, else Search::ring is used.
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

template <bool kWide, class Ring>
inline void walk_pixels(const Walk& c, [[maybe_unused]] Ring ring, size_t j0, size_t j1, uint64_t& steps, uint64_t& invalid) {
  const ReflectionDepthImage& key = c.key;
  const Search& s = c.s;
  const OffsetBuffer* const previous = c.previous;
  const OffsetBuffer* const earlier = c.earlier;
  const BestMatchOptions& options = c.options;
  const bool warm = c.warm, extrapolate = c.extrapolate;
  const int w = c.w, max_steps = c.max_steps;
  const float focal = c.focal;
  vec2* const offsets = c.offsets;
  uint8_t* const valid = c.valid;
  // key.pixels is row-major ascending: follow the row instead of dividing per pixel.
  int y = j0 < j1 ? int(key.pixels[j0] / size_t(w)) : 0;
  size_t row = size_t(y) * size_t(w);
  for (size_t j = j0; j < j1; ++j) {
    const size_t i = key.pixels[j];
    while (i >= row + size_t(w)) ++y, row += size_t(w);
    const int x = int(i - row);
    const uint32_t object = s.objects[i];
    const vec3 r = key.reflected[j];
    int cx = x, cy = y;
    if (warm) {  // INVALID pixels too: their end point saves the next walk
      const int px = x + round_offset(previous->offset[i].x), py = y + round_offset(previous->offset[i].y);
      if (s.same(px, py, object)) cx = px, cy = py;
    }
    // The wide ring gives the start's distance with its first ring (its centre lane) unless
    // the extrapolated guess needs it first.
    const bool centre_from_ring = kWide && !extrapolate;
    float former = centre_from_ring ? 0.0f : s.distance(cx, cy, r);
    if (extrapolate) {  // steady motion: the offset moves on by its last change
      const vec2 guess = 2.0f * previous->offset[i] - earlier->offset[i];
      const int gx = x + round_offset(guess.x), gy = y + round_offset(guess.y);
      if ((gx != cx || gy != cy) && s.same(gx, gy, object)) {
        const float d = s.distance(gx, gy, r);
        if (d < former) former = d, cx = gx, cy = gy;
      }
    }
    bool converged = false, inside = true;  // inside: the last ring was all on the reflector
    // The last step's 3×3 distances (centre included): on convergence they are the end
    // point's neighbours, which the sub-pixel fit reads again. Each step evaluates its
    // whole ring at once (SIMD): cells shared with the previous square get the same bits.
    float around[3][3] = {};
    around[1][1] = former;
    for (int step = 0; step < max_steps; ++step) {
      float d8[8];
      if constexpr (kWide) {
        inside = ring(cx, cy, object, r, d8, centre_from_ring && step == 0 ? &former : nullptr);
      } else {
        inside = s.ring(cx, cy, object, r, d8);
      }
      int bx = cx, by = cy;
      float best = kInf;
      for (int k = 0; k < 8; ++k) {
        around[kRing[k][1] + 1][kRing[k][0] + 1] = d8[k];
        if (d8[k] < best) best = d8[k], bx = cx + kRing[k][0], by = cy + kRing[k][1];
      }
      around[1][1] = former;
      if (!(best < former)) {  // local minimum (ties stop too: no cycles)
        converged = true;
        break;
      }
      former = best;
      cx = bx;
      cy = by;
      ++steps;
    }
    bool ok = converged;
    if (ok) {
      // On the silhouette border the true minimum may lie outside the reflector: keep
      // the match only if the reflected ray through W_c misses E_cur by ≤ tolerance
      // key pixels (distance scaled back to W_c by similar triangles).
      // (the end point's 3×3 is on the reflector but for the ring's cells outside)
      if (!inside) {
        const vec3 wc = rgb_at(key.position, cx, cy), nc = rgb_at(key.normal, cx, cy);
        const vec3 m = r - 2.0f * glm::dot(r - wc, nc) * nc;
        const float scale = glm::length(wc - m) / std::max(glm::length(s.eye - m), 1e-6f);
        const float miss_px = former * scale * focal / std::max(key.depth.at(cx, cy), 1e-6f);
        ok = miss_px <= options.border_tolerance_px;
      }
    }
    if (!ok) {
      ++invalid;
      offsets[i] = vec2(float(cx - x), float(cy - y));
      valid[i] = 0;
      continue;
    }
    vec2 sub(0.0f);
    if (options.subpixel) {
      auto sq = [&](int dx, int dy) { return around[dy + 1][dx + 1] * around[dy + 1][dx + 1]; };
      const float b = former * former;
      const float l = sq(-1, 0), rr = sq(1, 0), u = sq(0, -1), dn = sq(0, 1);
      // An (almost) exact match stays put: near a zero of the distance its square is
      // far from a parabola where the reflection is close (small s.r).
      auto exact = [&](float p, float q) { return b <= kExactMatch * std::min(p, q); };
      if (std::isfinite(l) && std::isfinite(rr) && !exact(l, rr)) sub.x = parabola_vertex(l, b, rr);
      if (std::isfinite(u) && std::isfinite(dn) && !exact(u, dn)) sub.y = parabola_vertex(u, b, dn);
    }
    offsets[i] = vec2(float(cx - x), float(cy - y)) + sub;
    valid[i] = 1;
  }
}

struct NoRing {};

void walk_pixels_sse(const Walk& c, size_t j0, size_t j1, uint64_t& steps, uint64_t& invalid) {
  walk_pixels<false>(c, NoRing{}, j0, j1, steps, invalid);
}

#if defined(PROXIMA_BEST_MATCH_AVX512)
// flatten: walk_pixels and WideRing inline here, in the avx512f context.
__attribute__((target("avx512f"), flatten)) void walk_pixels_avx512(const Walk& c, size_t j0, size_t j1,
                                                                      uint64_t& steps, uint64_t& invalid) {
  walk_pixels<true>(c, WideRing{c.s}, j0, j1, steps, invalid);
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
