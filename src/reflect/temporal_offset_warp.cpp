// Reflection offset (thesis ch. 5 §5.4.2): grid-mesh forward warp by the best-match offsets.
// A small screen-space triangle rasterizer of its own: raster/ rasterizes scene geometry
// through a camera, while these triangles live on the key frame's pixel grid already.
#include "proxima/reflect/temporal_offset_warp.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"

namespace proxima {

namespace {

constexpr int kBandRows = 16;
// Pixel centres this close outside an edge still count as covered, so a vertex sitting on
// a pixel centre (offset 0) covers it despite rounding.
constexpr float kEdgeSlack = 1e-3f;

// A key pixel as a mesh vertex: its centre moved by its offset, depth s.d + s.r, s.Lr.
struct Vertex {
  vec2 p;
  float z;
  vec3 lr;
};

Vertex vertex_at(const IntermediateReflection& image, uint32_t j) {
  return Vertex{image.point[j], image.sample[j].z, image.sample[j].lr};
}

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

// Corners of the two triangles of grid quad (x, y)–(x+1, y+1), split along its main diagonal.
constexpr int kCorner[2][3][2] = {{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {1, 1}, {0, 1}}};

// Lr at barycentrics b (unnormalised, ≥ 0, not all 0): the blend, or on an edge triangle
// the corner with the largest weight (ties: the first), so no value between the sides.
vec3 reconstruct(const Vertex v[3], const float b[3], bool nearest) {
  if (nearest) {
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if (b[j] > b[k]) k = j;
    return v[k].lr;
  }
  return (b[0] * v[0].lr + b[1] * v[1].lr + b[2] * v[2].lr) / (b[0] + b[1] + b[2]);
}

}  // namespace

bool edge_triangle(const ReflectionDepthImage& key, const int corner_x[3], const int corner_y[3], float contrast) {
  if (!(contrast < kInf)) return false;
  for (int c = 0; c < 3; ++c) {
    float lo = kInf, hi = -kInf;
    for (int k = 0; k < 3; ++k) {
      const float v = key.specular.at(corner_x[k], corner_y[k]) * key.radiance.at(corner_x[k], corner_y[k], c);
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    if (hi - lo > contrast) return true;
  }
  return false;
}

float blend_risk(const BlendSamples& blend, vec3 value, float s, vec3 base) {
  auto display = [&](vec3 lr, int c) { return linear_to_srgb(std::clamp(base[c] + s * lr[c], 0.0f, 1.0f)); };
  float total = 0.0f;
  for (int k = 0; k < blend.n; ++k) total += blend.w[k];
  if (!(total > 0.0f)) return 0.0f;
  float most = 0.0f;
  for (int c = 0; c < 3; ++c) {
    const float at = display(value, c);
    float sum = 0.0f;
    for (int k = 0; k < blend.n; ++k) sum += blend.w[k] * std::abs(display(blend.lr[k], c) - at);
    most = std::max(most, sum / total);
  }
  return 255.0f * most;
}

namespace {

// linear_to_srgb on [0, 1] by linear interpolation in a table of kSrgbSteps + 1 exact values:
// off by at most kSrgbError. The chord's error is ≤ h²/8·max|D''| per step h = 1/4096
// (D'' = −0.256·l^−1.58 from l = 0.0031308 up: 1.7·10⁻⁵), ≤ h·ΔD'/4 on the step holding the
// linear segment's kink (slopes 12.92 vs 12.70: 1.4·10⁻⁵), plus float rounding (≤ 10⁻⁶);
// the bound is 3× the sum, checked by a test against every 2⁻¹⁸ step.
constexpr int kSrgbSteps = 4096;
constexpr float kSrgbError = 1e-4f;

const float* srgb_table() {
  static const std::array<float, kSrgbSteps + 1> table = [] {
    std::array<float, kSrgbSteps + 1> t{};
    for (int j = 0; j <= kSrgbSteps; ++j) t[size_t(j)] = linear_to_srgb(float(j) / float(kSrgbSteps));
    return t;
  }();
  return table.data();
}

// x in [0, 1] (not NaN).
float srgb_approx(const float* table, float x) {
  const float t = x * float(kSrgbSteps);
  const int j = std::min(int(t), kSrgbSteps - 1);
  return table[j] + (t - float(j)) * (table[j + 1] - table[j]);
}

}  // namespace

float linear_to_srgb_approx(float l) { return srgb_approx(srgb_table(), l); }

float linear_to_srgb_approx_error() { return kSrgbError; }

namespace {

// Σ_k w_k·|x_k − x| per channel, x = base + s·Lr as the risk's display() computes it, all
// three below `bound` / kSlopeBound (`bound`: (limit − kClearMargin)·Σ w). Both display curves
// are nearly 12.92-Lipschitz on [0, 1]: linear_to_srgb's linear piece has slope 12.92, its
// power piece at most 12.70 (at its start), its jump between them is 2·10⁻⁸ and powf is
// within 1.5·10⁻⁷ of it (checked on every float of [0, 1]); the table's chords are then
// steeper by at most 2·1.5·10⁻⁷·4096 + 10⁻⁴ and its interpolation adds ≤ 2.5·10⁻⁷. The clamp
// is 1-Lipschitz, so each table term |D(x_k) − D(x)| ≤ 12.922·|x_k − x| + 5·10⁻⁷, and the
// table's risk ≤ 255·12.922/kSlopeBound·(limit − kClearMargin) + 1.3·10⁻⁴ (the float rounding
// of these few sums and products: ~10⁻⁶ relative, inside the 3% between 255·12.922 and
// kSlopeBound) < limit − kMargin: blend_risk_exceeds's table decides "no" there. NaN or
// infinite x never pass.
constexpr float kSlopeBound = 3400.0f;
constexpr float kClearMargin = 0.125f;

bool below_by_slope(const BlendSamples& blend, vec3 value, float s, vec3 base, float bound) {
  float sum[3];
  for (int c = 0; c < 3; ++c) {
    const float at = base[c] + s * value[c];
    float t = 0.0f;
    for (int k = 0; k < blend.n; ++k) t += blend.w[k] * std::abs(base[c] + s * blend.lr[k][c] - at);
    sum[c] = t;
  }
  return kSlopeBound * sum[0] < bound && kSlopeBound * sum[1] < bound && kSlopeBound * sum[2] < bound;
}

}  // namespace

bool blend_risk_exceeds(const BlendSamples& blend, vec3 value, float s, vec3 base, float limit) {
  // The risk from the table instead of powf is off by at most 255·2·kSrgbError (each term's
  // two display values by kSrgbError, a weighted mean of non-negative weights, a max over
  // channels) plus the float rounding of ≤ 4-term sums (~10⁻⁶·255): the margin is twice
  // that. Outside it the decision is the exact one; inside it (and for NaN, negative
  // weights, or no weight) the exact risk decides.
  constexpr float kMargin = 2.0f * 255.0f * 2.0f * kSrgbError;
  static_assert(kMargin + 0.02f < kClearMargin && 255.0f * 12.922f < 0.97f * kSlopeBound);
  const float* table = srgb_table();
  float total = 0.0f;
  bool usable = true;
  for (int k = 0; k < blend.n; ++k) total += blend.w[k], usable = usable && blend.w[k] >= 0.0f;
  if (usable && total > 0.0f && total < kInf) {
    // Most blends are of similar samples: the display curve's slope settles those first.
    if (below_by_slope(blend, value, s, base, (limit - kClearMargin) * total)) return false;
    auto display = [&](vec3 lr, int c, bool& ok) {
      const float x = base[c] + s * lr[c];
      ok = ok && x == x;
      return srgb_approx(table, x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f);
    };
    bool ok = true;
    float most = 0.0f;
    for (int c = 0; c < 3; ++c) {
      const float at = display(value, c, ok);
      float sum = 0.0f;
      for (int k = 0; k < blend.n; ++k) sum += blend.w[k] * std::abs(display(blend.lr[k], c, ok) - at);
      most = std::max(most, sum / total);
    }
    const float risk = 255.0f * most;
    if (ok && risk < limit - kMargin) return false;
    if (ok && risk > limit + kMargin && risk < kInf) return true;
  }
  return blend_risk(blend, value, s, base) > limit;
}

namespace {

// warped_radiance_at's value at q of triangle `id` (corners `corner` in key.pixels, edge
// functions e, q inside or within the slack), and the blend it is.
void triangle_value(const WarpedMesh& mesh, uint32_t id, const uint32_t corner[3], const float e[3],
                    vec3& radiance, BlendSamples* blend) {
  const IntermediateReflection& image = *mesh.image;
  Vertex v[3];
  for (int k = 0; k < 3; ++k) v[k] = vertex_at(image, corner[k]);
  const float b[3] = {std::max(e[0], 0.0f), std::max(e[1], 0.0f), std::max(e[2], 0.0f)};
  bool nearest = false;
  if (mesh.edge_contrast < kInf) {  // edge_triangle is false otherwise
    const uint32_t w = uint32_t(image.triangle.width()), quad = id / 2u, half = id % 2u;
    const int qx = int(quad % w), qy = int(quad / w);
    int cx[3], cy[3];
    for (int k = 0; k < 3; ++k) cx[k] = qx + kCorner[half][k][0], cy[k] = qy + kCorner[half][k][1];
    nearest = edge_triangle(*mesh.key, cx, cy, mesh.edge_contrast);
  }
  radiance = reconstruct(v, b, nearest);
  if (blend) {
    blend->n = 3;
    for (int k = 0; k < 3; ++k) blend->lr[k] = v[k].lr, blend->w[k] = b[k];
  }
}

}  // namespace

bool warped_radiance_at(const WarpedMesh& mesh, vec2 q, vec3& radiance, BlendSamples* blend) {
  const IntermediateReflection& image = *mesh.image;
  const int w = image.triangle.width(), h = image.triangle.height();
  const int cx = int(std::floor(q.x)), cy = int(std::floor(q.y));
  const uint8_t* state = image.state.data().data();
  const uint32_t* triangle = image.triangle.data().data();
  const uint32_t* index = image.index.data();
  const vec2* point = image.point.data();
  // The triangles stored at the reliable pixels of the 3×3 around q inside the image, row by
  // row (a splatted point stores none). One stored at two of them is tested twice: the same
  // test, so the same answer (the first that contains q wins).
  const int x_lo = std::max(cx - 1, 0), x_hi = std::min(cx + 1, w - 1);
  const int y_lo = std::max(cy - 1, 0), y_hi = std::min(cy + 1, h - 1);
  uint32_t ids[9];
  int m = 0;
  for (int y = y_lo; y <= y_hi; ++y)
    for (int x = x_lo; x <= x_hi; ++x) {
      const size_t at = size_t(y) * size_t(w) + size_t(x);
      ids[m] = triangle[at];
      m += state[at] == kWarpReliable && ids[m] != kNoWarpTriangle;
    }
  // Corner indices in key.pixels: those are row-major, so a corner's right neighbour (also
  // reflective) is the next index: two map reads, not three.
  auto corners = [&](uint32_t id, uint32_t corner[3]) {
    const uint32_t quad = id / 2u, half = id % 2u;
    const uint32_t first = index[quad], diagonal = index[size_t(quad) + size_t(w) + 1u];
    corner[0] = first;
    corner[1] = half == 0u ? first + 1u : diagonal;
    corner[2] = half == 0u ? diagonal : diagonal - 1u;
  };
  // The test, with edge functions e_k signed by the orientation: a degenerate triangle
  // (|area2| < 1e-12) covers nothing; q counts as inside when no e_k < −kEdgeSlack·√|area2|
  // (a pixel centre this close outside an edge still counts; NaN is never outside). That is
  // the warp's rule: strictly inside no e_k is negative, so its slack 0 there changes nothing,
  // and an e_k below −kEdgeSlack·max(1, |area2|) is below the slack too.
#if defined(__SSE2__)
  // Four triangles at a time, in the same IEEE single operations as the scalar test (no
  // contraction on SSE2): the same edge functions, bit for bit.
  const __m128 sign = _mm_set1_ps(-0.0f), qx = _mm_set1_ps(q.x), qy = _mm_set1_ps(q.y);
  for (int k0 = 0; k0 < m; k0 += 4) {
    const int lanes = std::min(4, m - k0);
    uint32_t corner[4][3];
    __m128 lo[3], hi[3];  // corners k of lanes 0, 1 and 2, 3 as x, y, x, y
    for (int l = 0; l < 4; ++l) {
      corners(ids[k0 + (l < lanes ? l : 0)], corner[l]);
      for (int k = 0; k < 3; ++k) {
        const __m64* p = reinterpret_cast<const __m64*>(&point[corner[l][k]]);
        if (l == 0) lo[k] = _mm_loadl_pi(_mm_setzero_ps(), p);
        if (l == 1) lo[k] = _mm_loadh_pi(lo[k], p);
        if (l == 2) hi[k] = _mm_loadl_pi(_mm_setzero_ps(), p);
        if (l == 3) hi[k] = _mm_loadh_pi(hi[k], p);
      }
    }
    __m128 px[3], py[3];
    for (int k = 0; k < 3; ++k) {
      px[k] = _mm_shuffle_ps(lo[k], hi[k], _MM_SHUFFLE(2, 0, 2, 0));
      py[k] = _mm_shuffle_ps(lo[k], hi[k], _MM_SHUFFLE(3, 1, 3, 1));
    }
    auto cross = [](__m128 ax, __m128 ay, __m128 bx, __m128 by) {
      return _mm_sub_ps(_mm_mul_ps(ax, by), _mm_mul_ps(ay, bx));
    };
    const __m128 area2 = cross(_mm_sub_ps(px[1], px[0]), _mm_sub_ps(py[1], py[0]), _mm_sub_ps(px[2], px[0]),
                               _mm_sub_ps(py[2], py[0]));
    const __m128 flip = _mm_and_ps(_mm_cmplt_ps(area2, _mm_setzero_ps()), sign);
    auto edge = [&](int a, int b) {
      return _mm_xor_ps(cross(_mm_sub_ps(px[b], px[a]), _mm_sub_ps(py[b], py[a]), _mm_sub_ps(qx, px[a]),
                              _mm_sub_ps(qy, py[a])),
                        flip);
    };
    __m128 e[3] = {edge(1, 2), edge(2, 0), edge(0, 1)};
    const __m128 size = _mm_andnot_ps(sign, area2);
    const __m128 outside = _mm_xor_ps(_mm_mul_ps(_mm_set1_ps(kEdgeSlack), _mm_sqrt_ps(size)), sign);
    const __m128 miss =
        _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(size, _mm_set1_ps(1e-12f)), _mm_cmplt_ps(e[0], outside)),
                  _mm_or_ps(_mm_cmplt_ps(e[1], outside), _mm_cmplt_ps(e[2], outside)));
    const unsigned hits = ~unsigned(_mm_movemask_ps(miss)) & ((1u << lanes) - 1u);
    if (hits) {
      const int l = std::countr_zero(hits);
      alignas(16) float ev[3][4];
      for (int k = 0; k < 3; ++k) _mm_store_ps(ev[k], e[k]);
      const float el[3] = {ev[0][l], ev[1][l], ev[2][l]};
      triangle_value(mesh, ids[k0 + l], corner[l], el, radiance, blend);
      return true;
    }
  }
#else
  for (int j = 0; j < m; ++j) {
    uint32_t corner[3];
    corners(ids[j], corner);
    const vec2 p[3] = {point[corner[0]], point[corner[1]], point[corner[2]]};
    const float area2 = cross2(p[1] - p[0], p[2] - p[0]);
    auto edge = [&](vec2 a, vec2 b) {
      const float e = cross2(b - a, q - a);
      return area2 < 0.0f ? -e : e;
    };
    const float e[3] = {edge(p[1], p[2]), edge(p[2], p[0]), edge(p[0], p[1])};
    const float outside = -(kEdgeSlack * std::sqrt(std::abs(area2)));
    if (std::abs(area2) < 1e-12f || e[0] < outside || e[1] < outside || e[2] < outside) continue;
    triangle_value(mesh, ids[j], corner, e, radiance, blend);
    return true;
  }
#endif
  return false;
}

namespace {

// Room in the per-key-pixel vectors for every pixel of the image (candidates: two per
// pixel), taken once: a key frame with more reflective pixels than the last then grows
// them in place. Reallocating copies into fresh pages, and first touching pages (page
// faults) cost more than the warp itself where the reflective area grows key frame after
// key frame (tens of ms at 1024²). Untouched reserved pages cost no memory.
void reserve_for_image(IntermediateReflection& out, size_t pixel_count) {
  if (out.point.capacity() >= pixel_count) return;
  out.point.reserve(pixel_count);
  out.valid.reserve(pixel_count);
  out.written.reserve(pixel_count);
  out.sample.reserve(pixel_count);
  out.flat.reserve(pixel_count);
  out.candidates.reserve(2 * pixel_count);
}

// The warp's tables that depend on the key frame (and options) only: built once per key
// frame, not per frame. The candidates keep the per-frame loop's triangle order.
void build_key_tables(const ReflectionDepthImage& key, const WarpOptions& options, IntermediateReflection& out) {
  const int w = key.object.width(), h = key.object.height();
  const std::vector<uint32_t>& pixels = key.pixels;
  const size_t n = pixels.size();
  out.sample.resize(n);
  out.flat.resize(n);
  out.index.resize(size_t(w) * size_t(h));  // read on reflective pixels only, each set here
  // The key's images as plain arrays (one channel each, radiance three).
  const uint32_t* object = key.object.data().data();
  const float* depth = key.depth.data().data();
  const float* distance = key.distance.data().data();
  const float* radiance = key.radiance.data().data();
  const float* specular = key.specular.data().data();
  const float* spread_image = key.spread.data().data();
  const float* lobe = key.lobe.data().data();
  uint32_t* index = out.index.data();
  WarpSample* sample = out.sample.data();
  // A glossy lobe averages over its cone: a reflector that bends the reflection by less
  // than the lobe's half-angle per pixel does not change a pixel's value much.
  const float pixel_angle = 1.0f / focal_length_px(key.camera);
  auto contrast = [&](int x, int y) {
    const size_t i = size_t(y) * size_t(w) + size_t(x);
    const uint32_t o = object[i];
    constexpr int kStep[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    float most = 0.0f;
    for (const auto& d : kStep) {
      const int nx = x + d[0], ny = y + d[1];
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      const size_t ni = size_t(ny) * size_t(w) + size_t(nx);
      if (object[ni] != o) continue;
      for (int c = 0; c < 3; ++c)
        most = std::max(most, std::abs(specular[i] * radiance[3 * i + size_t(c)] -
                                       specular[ni] * radiance[3 * ni + size_t(c)]));
    }
    return most;
  };
  // key.pixels are row-major: a pixel's row follows without a division.
  uint32_t y = 0, row_start = 0;
  for (size_t j = 0; j < n; ++j) {
    const uint32_t i = pixels[j];
    while (i - row_start >= uint32_t(w)) ++y, row_start += uint32_t(w);
    const int x = int(i - row_start);
    index[i] = uint32_t(j);
    sample[j] = WarpSample{depth[i] + distance[i], vec3(radiance[3 * size_t(i)], radiance[3 * size_t(i) + 1],
                                                        radiance[3 * size_t(i) + 2])};
    const float spread = spread_image[i];
    out.flat[j] = spread <= options.spread_limit || spread * pixel_angle <= lobe[i] ||
                  contrast(x, int(y)) <= options.curved_contrast;
  }
  const uint8_t* flat = out.flat.data();
  const float jump = 1.0f + options.depth_discontinuity;
  auto continuous = [&](std::array<float, 3> v) {
    const auto [lo, hi] = std::minmax({v[0], v[1], v[2]});
    return hi <= jump * lo;
  };
  const bool edges = options.edge_contrast < kInf;  // else edge_triangle is false
  out.candidates.clear();
  y = 0, row_start = 0;
  for (size_t j = 0; j < n; ++j) {  // (x, y): both halves' first corner, reflective
    const uint32_t i = pixels[j];
    while (i - row_start >= uint32_t(w)) ++y, row_start += uint32_t(w);
    const int x = int(i - row_start);
    if (int(y) + 1 >= h || x + 1 >= w) continue;
    const uint32_t o = object[i];
    const size_t diagonal = size_t(i) + size_t(w) + 1u;  // both halves' corner
    if (o == kNoReflector || object[diagonal] != o) continue;
    for (int half = 0; half < 2; ++half) {
      const size_t third = half == 0 ? size_t(i) + 1u : size_t(i) + size_t(w);  // (x+1, y) or (x, y+1)
      if (object[third] != o) continue;
      const size_t at[3] = {size_t(i), half == 0 ? third : diagonal, half == 0 ? diagonal : third};
      WarpCandidate& cand = out.candidates.emplace_back();  // filled in place
      for (int k = 0; k < 3; ++k) cand.corner[k] = index[at[k]];
      cand.half = uint8_t(half);
      const float za = sample[cand.corner[0]].z, zb = sample[cand.corner[1]].z, zc = sample[cand.corner[2]].z;
      if (!continuous({depth[at[0]], depth[at[1]], depth[at[2]]}) || !continuous({za, zb, zc})) {
        cand.flags = kCandidateDiscontinuous;
      } else {
        if (!flat[cand.corner[0]] || !flat[cand.corner[1]] || !flat[cand.corner[2]]) cand.flags |= kCandidateCurved;
        if (edges) {
          int cx[3], cy[3];
          for (int k = 0; k < 3; ++k) cx[k] = x + kCorner[half][k][0], cy[k] = int(y) + kCorner[half][k][1];
          if (edge_triangle(key, cx, cy, options.edge_contrast)) cand.flags |= kCandidateEdge;
        }
      }
    }
  }
}


// int(std::ceil(x)) and int(std::floor(x)), the same for every x, without the rounding
// sequence SSE2 (no roundss) inlines: within int range truncation and one comparison.
int ceil_int(float x) {
  if (!(std::abs(x) < 2147483648.0f)) return int(std::ceil(x));  // beyond int range, NaN: as before
  const int t = int(x);
  return t + int(float(t) < x);
}
int floor_int(float x) {
  if (!(std::abs(x) < 2147483648.0f)) return int(std::floor(x));
  const int t = int(x);
  return t - int(float(t) > x);
}

// A triangle the per-frame tests kept, in the candidates' order: what its raster needs.
struct LiveTriangle {
  uint32_t candidate;
  uint8_t state;  // WarpState its pixels get
  bool nearest;   // an edge triangle under ReflectedEdgeRule::kNearest
  int r0, r1;     // the pixel rows whose centres its bounding box may hold (clipped to the image)
};

// What the raster reads and writes: the per-frame and per-key-frame arrays as plain pointers
// (stores through the uint8_t state image may alias anything: no reloads through `out`).
struct WarpTarget {
  float* depth;
  float* radiance;
  uint8_t* state;
  uint32_t* triangle;
  const uint32_t* object;   // the key's reflector ids
  const uint32_t* pixels;   // key.pixels
  const WarpSample* sample;
  int w;
};

// Four floats as one value: a key sample's (z, Lr) blended in one go. Per lane the same
// IEEE operations as the scalar expressions, so the same bits.
typedef float Float4 __attribute__((vector_size(16)));
static_assert(sizeof(WarpSample) == sizeof(Float4));

Float4 load_sample(const WarpSample& s) { return std::bit_cast<Float4>(s); }

Float4 splat4(float x) { return Float4{x, x, x, x}; }

// Rasterizes one live triangle into pixel rows [py0, py1] (within its bounding box). A
// pixel's result depends only on the triangles that cover it, in the order they come: the
// rows a call covers (a band, or the whole box) do not change it.
// p0..p2: its corners' warped positions, area2 = cross2(p1 − p0, p2 − p0).
inline __attribute__((always_inline)) void raster_triangle(const WarpTarget& to, const WarpCandidate& cand, vec2 p0,
                                                           vec2 p1, vec2 p2, float area2, uint8_t tri_state,
                                                           bool nearest, int py0, int py1) {
  if (std::abs(area2) < 1e-12f) return;  // collapsed: covers no pixel centre
  const float xmin = std::min({p0.x, p1.x, p2.x}), xmax = std::max({p0.x, p1.x, p2.x});
  const int px0 = std::max(0, ceil_int(xmin - 0.5f - kEdgeSlack));
  const int px1 = std::min(to.w - 1, floor_int(xmax - 0.5f + kEdgeSlack));
  if (px0 > px1) return;
  const uint32_t quad = to.pixels[cand.corner[0]];
  const uint32_t id = 2u * quad + uint32_t(cand.half);
  const uint32_t reflector = to.object[quad];
  const vec2 d0 = p2 - p1, d1 = p0 - p2, d2 = p1 - p0;  // edges opposite corners 0, 1, 2
  const bool flip = area2 < 0.0f;
  // The slack (a square root) only for centres outside an edge; 1/|area2| only on a hit.
  float slack = -1.0f, inv = 0.0f;
  for (int py = py0; py <= py1; ++py) {
    const float cy = float(py) + 0.5f;
    const float y0 = cy - p1.y, y1 = cy - p2.y, y2 = cy - p0.y;
    const size_t row = size_t(py) * size_t(to.w);
    for (int px = px0; px <= px1; ++px) {
      const float cx = float(px) + 0.5f;
      // Barycentrics from edge functions, signed by the triangle's orientation.
      float e0 = d0.x * y0 - d0.y * (cx - p1.x), e1 = d1.x * y1 - d1.y * (cx - p2.x),
            e2 = d2.x * y2 - d2.y * (cx - p0.x);
      if (flip) e0 = -e0, e1 = -e1, e2 = -e2;
      if (!(e0 >= 0.0f && e1 >= 0.0f && e2 >= 0.0f)) {  // inside: no slack needed
        if (slack < 0.0f) slack = kEdgeSlack * std::sqrt(std::abs(area2));  // in edge-function units
        if (e0 < -slack || e1 < -slack || e2 < -slack) continue;
      }
      const size_t at = row + size_t(px);
      // Offsets stay on their reflector, so a pixel only takes its own reflector's
      // triangles: another's (a floor mirror warped over a ball standing on it) would
      // win the depth test there with the wrong reflection.
      if (to.object[at] != reflector) continue;
      if (inv == 0.0f) inv = 1.0f / std::abs(area2);
      const float b[3] = {std::max(e0, 0.0f) * inv, std::max(e1, 0.0f) * inv, std::max(e2, 0.0f) * inv};
      const float sum = b[0] + b[1] + b[2];
      // (b0·z0 + b1·z1 + b2·z2) / sum, and the same of Lr (reconstruct's blend), in one.
      const Float4 blend = (splat4(b[0]) * load_sample(to.sample[cand.corner[0]]) +
                            splat4(b[1]) * load_sample(to.sample[cand.corner[1]]) +
                            splat4(b[2]) * load_sample(to.sample[cand.corner[2]])) /
                           splat4(sum);
      const float z = blend[0];
      if (!(z < to.depth[at])) continue;  // ties: the first triangle keeps the pixel
      to.depth[at] = z;
      float* lr = to.radiance + 3 * at;
      if (nearest) {  // reconstruct's nearest corner: the largest weight (ties: the first)
        int k = 0;
        for (int j = 1; j < 3; ++j)
          if (b[j] > b[k]) k = j;
        const vec3 corner = to.sample[cand.corner[k]].lr;
        lr[0] = corner[0], lr[1] = corner[1], lr[2] = corner[2];
      } else {
        lr[0] = blend[1], lr[1] = blend[2], lr[2] = blend[3];
      }
      to.state[at] = tri_state;
      to.triangle[at] = id;
    }
  }
}

}  // namespace

IntermediateReflection warp_reflections(const ReflectionDepthImage& key, const OffsetBuffer& offsets,
                                        const WarpOptions& options) {
  IntermediateReflection out;
  warp_reflections_into(key, offsets, options, out);
  return out;
}

void warp_reflections_into(const ReflectionDepthImage& key, const OffsetBuffer& offsets, const WarpOptions& options,
                           IntermediateReflection& out) {
  const int w = key.object.width(), h = key.object.height();
  const bool same_size = out.state.width() == w && out.state.height() == h;
  const bool same_key = key.serial != 0 && out.key_serial == key.serial && out.index.size() == size_t(w) * size_t(h);
  // Only the last warp's key's reflective pixels can have been written (a pixel takes only
  // its own reflector's triangles and splats): reset those, not four whole images per frame.
  // Under the same key they are this key's pixels: reset with the per-frame fill below.
  const bool reset_in_fill = same_size && same_key;
  if (!same_size) {
    out.radiance = ImageF(w, h, 3, 0.0f);
    out.depth = ImageF(w, h, 1, kInf);
    out.state = ImageU8(w, h, 1, kWarpEmpty);
    out.triangle = ImageU32(w, h, 1, kNoWarpTriangle);
  }
  float* const radiance = out.radiance.data().data();
  float* const depth = out.depth.data().data();
  uint8_t* const state = out.state.data().data();
  uint32_t* const triangle = out.triangle.data().data();
  auto reset = [&](uint32_t i) {
    radiance[3 * size_t(i)] = radiance[3 * size_t(i) + 1] = radiance[3 * size_t(i) + 2] = 0.0f;
    depth[i] = kInf;
    state[i] = kWarpEmpty;
    triangle[i] = kNoWarpTriangle;
  };
  if (same_size && !reset_in_fill)
    for (const uint32_t i : out.written) reset(i);
  reserve_for_image(out, size_t(w) * size_t(h));
  if (!same_key) out.written.assign(key.pixels.begin(), key.pixels.end());
  out.triangles = out.stretched = out.curved = out.discontinuous = out.edges = 0;
  const std::vector<uint32_t>& pixels = key.pixels;
  const size_t n = pixels.size();
  const uint32_t* object = key.object.data().data();
  const uint32_t key_options[4] = {std::bit_cast<uint32_t>(options.depth_discontinuity),
                                   std::bit_cast<uint32_t>(options.spread_limit),
                                   std::bit_cast<uint32_t>(options.curved_contrast),
                                   std::bit_cast<uint32_t>(options.edge_contrast)};
  if (!same_key || !std::equal(key_options, key_options + 4, out.key_options))
    build_key_tables(key, options, out);
  std::copy(key_options, key_options + 4, out.key_options);
  out.key_serial = key.serial;

  // Per frame: the vertices' positions and validity, compact in key.pixels order. The
  // pixels are row-major: their row follows without a division.
  out.point.resize(n);
  out.valid.resize(n);
  {
    vec2* point = out.point.data();
    uint8_t* valid_out = out.valid.data();
    const vec2* offset = offsets.offset.data();
    const uint8_t* offset_valid = offsets.valid.data();
    uint32_t y = 0, row_start = 0;
    for (size_t j = 0; j < n; ++j) {
      const uint32_t i = pixels[j];
      while (i - row_start >= uint32_t(w)) ++y, row_start += uint32_t(w);
      point[j] = vec2(float(i - row_start) + 0.5f, float(y) + 0.5f) + offset[i];
      valid_out[j] = offset_valid[i];
      if (reset_in_fill) reset(i);
    }
  }
  const uint8_t* valid = out.valid.data();

  // Triangles: quad (x, y)–(x+1, y+1) split along its main diagonal; id = 2·quad + half.
  // The per-frame tests (sequential: a fixed order) keep the live ones in the candidates'
  // order. The kept memory stays from call to call on this thread (no allocation per frame).
  // (A reference: the raster's worker threads must read the caller's list, not their own.)
  static thread_local std::vector<LiveTriangle> live_kept;
  std::vector<LiveTriangle>& live = live_kept;
  live.clear();
  // One thread: each triangle drawn as soon as it is kept, into all its rows.
  const WarpTarget to{depth, radiance, state, triangle, object, pixels.data(), out.sample.data(), w};
  const int bands = (h + kBandRows - 1) / kBandRows;
  const bool one_pass = active_threads() <= 1 || bands <= 1;
  const bool edge_recompute_rule = options.edge_rule == ReflectedEdgeRule::kRecompute;
  const float stretch_area = options.stretch_limit * 0.5f;  // original area: ½ pixel²
  const std::vector<WarpCandidate>& candidates = out.candidates;
  const vec2* point = out.point.data();
  // Counted here, stored at the end (stores through the state image could alias `out`).
  uint64_t triangles = 0, stretched_count = 0, curved_count = 0, discontinuous = 0, edges = 0;
  for (size_t t = 0; t < candidates.size(); ++t) {
    const WarpCandidate& cand = candidates[t];
    if (!valid[cand.corner[0]] || !valid[cand.corner[1]] || !valid[cand.corner[2]]) continue;
    if (cand.flags & kCandidateDiscontinuous) {
      ++discontinuous;
      continue;
    }
    ++triangles;
    const vec2 a = point[cand.corner[0]], b = point[cand.corner[1]], c = point[cand.corner[2]];
    const float area2 = cross2(b - a, c - a);
    const float area = 0.5f * std::abs(area2);
    const bool stretched = !(area <= stretch_area);
    const bool curved = (cand.flags & kCandidateCurved) != 0;
    const bool edge = (cand.flags & kCandidateEdge) != 0;
    const bool edge_recompute = edge && edge_recompute_rule;
    const uint8_t tri_state = curved           ? kWarpCurved
                              : stretched      ? kWarpUnreliable
                              : edge_recompute ? kWarpEdge
                                               : kWarpReliable;
    stretched_count += stretched;
    curved_count += curved;
    edges += edge;
    const float ymin = std::min({a.y, b.y, c.y}), ymax = std::max({a.y, b.y, c.y});
    const int r0 = std::max(0, ceil_int(ymin - 0.5f - kEdgeSlack));
    const int r1 = std::min(h - 1, floor_int(ymax - 0.5f + kEdgeSlack));
    if (r0 > r1) continue;
    if (one_pass)
      raster_triangle(to, cand, a, b, c, area2, tri_state, edge && !edge_recompute, r0, r1);
    else
      live.push_back({uint32_t(t), tri_state, edge && !edge_recompute, r0, r1});
  }
  out.triangles = triangles, out.stretched = stretched_count, out.curved = curved_count;
  out.discontinuous = discontinuous, out.edges = edges;

  // Each pixel takes the triangles covering it in the candidates' order whatever the rows
  // are split into: one pass on one thread, fixed row bands on more (the same result).
  if (!one_pass) {
    // Bin each into the row bands its bounding box touches, in order (a counting sort).
    static thread_local std::vector<uint32_t> band_start_kept, band_list_kept;
    std::vector<uint32_t>& band_start = band_start_kept;
    std::vector<uint32_t>& band_list = band_list_kept;
    band_start.assign(size_t(bands) + 1, 0u);
    for (const LiveTriangle& t : live)
      for (int band = t.r0 / kBandRows; band <= t.r1 / kBandRows; ++band) ++band_start[size_t(band) + 1];
    for (int band = 0; band < bands; ++band) band_start[size_t(band) + 1] += band_start[size_t(band)];
    band_list.resize(band_start[size_t(bands)]);
    {
      std::vector<uint32_t> next(band_start.begin(), band_start.end() - 1);
      for (size_t k = 0; k < live.size(); ++k)
        for (int band = live[k].r0 / kBandRows; band <= live[k].r1 / kBandRows; ++band)
          band_list[next[size_t(band)]++] = uint32_t(k);
    }
    parallel_for(size_t(bands), 1, [&](size_t band_begin, size_t band_end) {
      for (size_t band = band_begin; band < band_end; ++band) {
        const int y_lo = int(band) * kBandRows, y_hi = std::min(h, y_lo + kBandRows);
        for (uint32_t k = band_start[band]; k < band_start[band + 1]; ++k) {
          const LiveTriangle& t = live[band_list[k]];
          const WarpCandidate& cand = candidates[t.candidate];
          const vec2 a = point[cand.corner[0]], b = point[cand.corner[1]], c = point[cand.corner[2]];
          raster_triangle(to, cand, a, b, c, cross2(b - a, c - a), t.state, t.nearest, std::max(y_lo, t.r0),
                          std::min(y_hi - 1, t.r1));
        }
      }
    });
  }
  // Valid samples no triangle reached (one-pixel-wide parts of a reflector, corners next
  // to a dropped triangle) still land as points on the pixel nearest their warped position.
  const uint8_t* flat = out.flat.data();
  const WarpSample* sample = out.sample.data();
  const uint8_t splat_flat = options.recompute_splats ? kWarpUnreliable : kWarpReliable;
  for (size_t j = 0; j < n; ++j) {
    const uint32_t i = pixels[j];
    if (object[i] == kNoReflector || !valid[j]) continue;
    const vec2 p = point[j];
    const int px = floor_int(p.x), py = floor_int(p.y);
    if (px < 0 || py < 0 || px >= w || py >= h) continue;
    const size_t at = size_t(py) * size_t(w) + size_t(px);
    if (state[at] != kWarpEmpty || object[at] != object[i]) continue;
    depth[at] = sample[j].z;
    const vec3 lr = sample[j].lr;
    for (int c = 0; c < 3; ++c) radiance[3 * at + size_t(c)] = lr[c];
    state[at] = !flat[j] ? uint8_t(kWarpCurved) : splat_flat;
  }
}

const char* reflected_edge_rule_name(ReflectedEdgeRule rule) {
  return rule == ReflectedEdgeRule::kRecompute ? "recompute" : "nearest";
}

ReflectedEdgeRule parse_reflected_edge_rule(const std::string& name, const char* flag) {
  for (ReflectedEdgeRule rule : {ReflectedEdgeRule::kNearest, ReflectedEdgeRule::kRecompute})
    if (name == reflected_edge_rule_name(rule)) return rule;
  fail_input(std::string(flag) + ": must be nearest or recompute");
}

}  // namespace proxima
