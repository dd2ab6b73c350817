// Phase 4 of Funkhouser's GIBR system (section 2): "synthetic images are generated from the
// radiance maps at interactive rates for an arbitrary viewpoint". The radiance maps are
// view-dependent texture maps (as the paper's system, after Debevec et al.); the blend
// weights and hole filling are documented in novel_view.h and docs/gibr.md.
#include "proxima/gibr/novel_view.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/raster/rasterizer.h"

namespace proxima::gibr {

using namespace proxima::visibility;

namespace {

struct GridF {
  vec3 origin, u, v;
  float inv_texel;
};

// Linear values of the 256 sRGB codes, unpack_srgb8 per channel: a table the blend's
// innermost loop reads inline (unpack_srgb8 is out of line in radiance_map.cpp). Built on
// first use, after radiance_map.cpp's statics.
const float* srgb_lut() {
  static const std::array<float, 256> lut = [] {
    std::array<float, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) t[i] = unpack_srgb8(i).x;
    return t;
  }();
  return lut.data();
}

// A layer of a polygon in the frame's ranked order, flat: its rectangle and texels, its
// photograph's eye (one indirection less per layer than through SampleLayer).
struct RankedLayer {
  int x0, y0, width, height;
  const uint32_t* rgba;
  vec3 eye;
  const SampleLayer* layer;
  const uint8_t* reach;  // layer->reach, null when empty
  int reach_columns;
};

// True when the layer's 2 × 2 around texel (ti, tj) — the texel left of and above tc − ½, as in
// the fast loop — surely holds no sample with alpha ≥ kExtrapolated, so sample_layer_both would
// find nothing: the sampler's 2 × 2 texels inside the rectangle lie within chessboard distance 2
// of q, (ti, tj) clamped to the rectangle (its i0 is ti − x0 up to float rounding, ±1), and every
// such sample is at least reach(q's block) from q. One byte per 16 texels read instead of a 2 × 2
// (~¾ of the layers near a pixel that hold no sample there, on floor).
inline bool surely_empty(const RankedLayer& L, int ti, int tj) {
  if (!L.reach) return false;
  const int qi = std::clamp(ti - L.x0, 0, L.width - 1), qj = std::clamp(tj - L.y0, 0, L.height - 1);
  return L.reach[size_t(qj / kReachBlock) * size_t(L.reach_columns) + size_t(qi / kReachBlock)] > 2;
}

// Bilinear samples of a layer at continuous texel coordinates, from one read of the 2 × 2
// texels around them: out[0] over the direct samples (alpha 0xFF), out[1] over direct and
// exact-visible ones (alpha ≥ kExtrapolated), weights renormalized; ok[m] false when none of
// the 2 × 2 holds such a sample.
// Branch-free over the 2 × 2 (a texel outside the rectangle or below the threshold adds weight 0,
// which leaves the sums' bits as skipping it would: colors are finite and ≥ 0).
inline void sample_layer_both(const RankedLayer& L, vec2 tc, const float* lut, bool ok[2], vec3 out[2]) {
  ok[0] = ok[1] = false;
  const float sx = tc.x - 0.5f - float(L.x0), sy = tc.y - 0.5f - float(L.y0);
  const float fx0 = std::floor(sx), fy0 = std::floor(sy);
  const int i0 = int(fx0), j0 = int(fy0);
  if (i0 < -1 || j0 < -1 || i0 >= L.width || j0 >= L.height) return;
  const float fx = sx - fx0, fy = sy - fy0;
  const float wx[2] = {1.0f - fx, fx}, wy[2] = {1.0f - fy, fy};
  vec3 c[2] = {vec3(0.0f), vec3(0.0f)};
  float wsum[2] = {0.0f, 0.0f};
  for (int k = 0; k < 4; ++k) {
    const int i = i0 + (k & 1), j = j0 + (k >> 1);
    const bool in = unsigned(i) < unsigned(L.width) && unsigned(j) < unsigned(L.height);
    const uint32_t t = L.rgba[in ? size_t(j) * size_t(L.width) + size_t(i) : 0];
    const uint32_t a = in ? t >> 24 : 0u;
    const float w = wx[k & 1] * wy[k >> 1];
    const float w0 = a >= 0xFFu ? w : 0.0f, w1 = a >= kExtrapolated ? w : 0.0f;
    const vec3 v(lut[t & 0xFF], lut[(t >> 8) & 0xFF], lut[(t >> 16) & 0xFF]);
    c[0] += w0 * v;
    wsum[0] += w0;
    c[1] += w1 * v;
    wsum[1] += w1;
  }
  for (int m = 0; m < 2; ++m)
    if (!(wsum[m] <= 1e-6f)) ok[m] = true, out[m] = c[m] / wsum[m];
}

// The sample with alpha ≥ min_alpha (kExtrapolated or kMixed) nearest to texel (ci, cj) within
// `radius` rings (ring by ring, row-major within a ring). Visits only the ring's cells inside the
// layer's rectangle — O(r) per ring, not the whole square — in that same order, and starts at
// the first ring that may hold a sample (SampleLayer::reach): for q, the texel of the rectangle
// nearest to c = (ci, cj), every sample t has d(c, t) ≥ d(c, q) and, as d(q, t) ≥ reach of q's
// block, d(c, t) ≥ reach − d(c, q) (d: chessboard distance). The rings skipped hold no sample, so
// the result is the plain search's.
bool nearest_sample(const SampleLayer& L, int ci, int cj, int radius, uint32_t min_alpha, vec3& out) {
  const int li = ci - L.x0, lj = cj - L.y0;  // layer-local
  const int qi = std::clamp(li, 0, L.width - 1), qj = std::clamp(lj, 0, L.height - 1);
  const int dq = std::max(std::abs(li - qi), std::abs(lj - qj));
  int start = dq;
  const std::vector<uint8_t>& reach = min_alpha >= kExtrapolated ? L.reach : L.reach_mixed;
  if (!reach.empty() && min_alpha >= kMixed)
    start = std::max(start, int(reach[size_t(qj / kReachBlock) * size_t(L.reach_columns()) + size_t(qi / kReachBlock)]) - dq);
  if (start > radius) return false;
  auto hit = [&](int i, int j) {
    const uint32_t t = L.rgba[size_t(j) * size_t(L.width) + size_t(i)];
    if ((t >> 24) < min_alpha) return false;
    out = unpack_srgb8(t);
    return true;
  };
  for (int r = start; r <= radius; ++r) {
    const int j0 = std::max(lj - r, 0), j1 = std::min(lj + r, L.height - 1);
    const int i0 = std::max(li - r, 0), i1 = std::min(li + r, L.width - 1);
    for (int j = j0; j <= j1; ++j) {
      if (j == lj - r || j == lj + r) {  // top or bottom row of the ring: all of it
        for (int i = i0; i <= i1; ++i)
          if (hit(i, j)) return true;
      } else {  // a middle row: its two ends
        if (li - r >= 0 && li - r < L.width && hit(li - r, j)) return true;
        if (li + r >= 0 && li + r < L.width && hit(li + r, j)) return true;
      }
    }
  }
  return false;
}

// The plain search nearest_sample replaces (whole square per ring): NovelViewOptions::fast = false.
bool nearest_sample_plain(const SampleLayer& L, int ci, int cj, int radius, uint32_t min_alpha, vec3& out) {
  for (int r = 0; r <= radius; ++r)
    for (int j = cj - r; j <= cj + r; ++j)
      for (int i = ci - r; i <= ci + r; ++i) {
        if (std::max(std::abs(i - ci), std::abs(j - cj)) != r || !L.has(i, j)) continue;
        const uint32_t t = L.rgba[size_t(j - L.y0) * size_t(L.width) + size_t(i - L.x0)];
        if ((t >> 24) < min_alpha) continue;
        out = unpack_srgb8(t);
        return true;
      }
  return false;
}

// Hole fills already found in a tile: the fill is a function of (polygon, nearest
// photograph's layer, texel), and neighboring pixels and samples of a hole usually share all
// three (texels span several pixels), so a small direct-mapped memo skips the repeated ring
// searches. Bits are unchanged: a hit returns what the search would.
struct HoleMemo {
  struct Entry {
    uint32_t p = kNone, best = 0;
    int ci = 0, cj = 0;
    bool got = false;
    vec3 color{0.0f};
  };
  static constexpr size_t kSize = 256;
  std::array<Entry, kSize> e;
  static size_t slot(uint32_t p, int ci, int cj) {
    return (size_t(p) * 73856093u ^ size_t(uint32_t(ci)) * 19349663u ^ size_t(uint32_t(cj)) * 83492791u) % kSize;
  }
};

}  // namespace

void rank_layers(const RadianceMaps& maps, const visibility::ModelPolygons& model, size_t p, const vec3& eye,
                 std::vector<std::pair<float, uint32_t>>& keyed) {
  const auto& layers = maps.layers[p];
  keyed.clear();
  if (layers.empty()) return;
  dvec3 c(0.0);
  for (const dvec3& q : model.polygons[p].vertices) c += q;
  const vec3 centroid(c / double(model.polygons[p].vertices.size()));
  const vec3 to_eye = glm::normalize(eye - centroid);
  for (uint32_t i = 0; i < layers.size(); ++i) {
    const vec3 to_photo = glm::normalize(maps.cameras[layers[i].photo].position - centroid);
    keyed.push_back({-glm::dot(to_photo, to_eye), i});
  }
  std::sort(keyed.begin(), keyed.end());
}

NovelView render_novel_view(const Scene& scene, const ModelPolygons& model, const RadianceMaps& maps,
                            const Camera& camera, const NovelViewOptions& options, NovelViewScratch* scratch) {
  NovelView nv;
  const int ss = options.supersample;
  if (ss < 1 || ss > 8) fail_input("novel view: supersample must be in 1..8");  // the CLI names its flag itself
  Stopwatch watch;
  RasterOptions ro;
  ro.outputs = kRasterDepthId;
  // Supersampled: the same camera at ss× the resolution puts its pixel centers at the cell
  // centers of a regular ss × ss grid in each pixel, as render_reference's supersampling.
  Camera fine = camera;
  fine.width = camera.width * ss;
  fine.height = camera.height * ss;
  NovelViewScratch own;
  RasterImages& img = (scratch ? *scratch : own).raster;
  rasterize(scene, fine, ro, img, AcceptAllFragments{});
  nv.raster_ms = watch.elapsed_ms();
  watch.restart();

  // Rank each polygon's layers by the angle at its centroid (closest direction first).
  const size_t np = model.polygons.size();
  const vec3 eye = camera.position;
  std::vector<uint32_t> offset(np + 1, 0), order;
  std::vector<GridF> grids(np);
  std::vector<std::pair<float, uint32_t>> keyed;
  for (size_t p = 0; p < np; ++p) {
    const TexelGrid& g = maps.grids[p];
    grids[p] = {vec3(g.origin), vec3(g.u), vec3(g.v), float(1.0 / g.texel)};
    const auto& layers = maps.layers[p];
    offset[p + 1] = offset[p] + uint32_t(layers.size());
    if (layers.empty()) continue;
    rank_layers(maps, model, p, eye, keyed);
    for (const auto& kv : keyed) order.push_back(kv.second);
  }
  std::vector<RankedLayer> ranked(order.size());
  for (size_t p = 0; p < np; ++p)
    for (uint32_t o = offset[p]; o < offset[p + 1]; ++o) {
      const SampleLayer& L = maps.layers[p][order[o]];
      ranked[o] = {L.x0, L.y0, L.width, L.height, L.rgba.data(), maps.cameras[L.photo].position, &L,
                   L.reach.empty() ? nullptr : L.reach.data(), L.reach_columns()};
    }
  const float* lut = srgb_lut();

  const int k = std::max(1, options.k);
  // Polygon seen by sample (x, y) of the fine raster, kNone for none.
  auto polygon_at = [&](int x, int y) {
    const uint32_t tri = img.triangle.at(x, y);
    return tri == kNoTriangle ? kNone : model.triangle_polygon[tri];
  };
  // The color of surface point w on polygon p: `hole` when no photograph's sample covers it,
  // `filled` when the hole fill found one.
  auto shade = [&](uint32_t p, const vec3& w, vec3& color, bool& hole, bool& filled, HoleMemo& memo) {
    const GridF& g = grids[p];
    const vec3 d = w - g.origin;
    const vec2 tc(glm::dot(d, g.u) * g.inv_texel, glm::dot(d, g.v) * g.inv_texel);
    const vec3 view = glm::normalize(eye - w);
    const auto& layers = maps.layers[p];
    vec3 sum(0.0f);
    float wsum = 0.0f;
    int found = 0;
    // Direct samples first; exact-visible (extrapolated) ones only where no photograph
    // has a direct sample (mixed last-resort samples never: holes only).
    if (options.fast) {
      // Both passes in one scan, each summed in its own order as below: a hole (pass 1)
      // does not scan P's layers twice.
      vec3 sum1(0.0f);
      float wsum1 = 0.0f;
      int found1 = 0;
      // The texel left of and above tc − ½ (as sample_layer_both's i0 + x0, j0 + y0 up to its
      // float rounding, hence a margin of one): layers whose rectangle is clearly not near it
      // are skipped before the sampler's float work.
      const int ti = int(std::floor(tc.x - 0.5f)), tj = int(std::floor(tc.y - 0.5f));
      for (uint32_t o = offset[p]; o < offset[p + 1] && found < k; ++o) {
        const RankedLayer& R = ranked[o];
        if (ti - R.x0 < -2 || ti - R.x0 > R.width || tj - R.y0 < -2 || tj - R.y0 > R.height) continue;
        if (surely_empty(R, ti, tj)) continue;
        bool ok[2];
        vec3 c[2] = {vec3(0.0f), vec3(0.0f)};
        sample_layer_both(R, tc, lut, ok, c);
        const bool use1 = ok[1] && found1 < k;
        if (!ok[0] && !use1) continue;
        const float cosv = glm::dot(glm::normalize(R.eye - w), view);
        const float wt = 1.0f / (1.0f - cosv + 1e-7f);
        if (ok[0]) sum += wt * c[0], wsum += wt, ++found;
        if (use1) sum1 += wt * c[1], wsum1 += wt, ++found1;
      }
      if (found == 0) sum = sum1, wsum = wsum1, found = found1;
    }
    for (int pass = 0; !options.fast && pass < 2 && found == 0; ++pass)
      for (uint32_t o = offset[p]; o < offset[p + 1] && found < k; ++o) {
        bool ok[2];
        vec3 cc[2] = {vec3(0.0f), vec3(0.0f)};
        sample_layer_both(ranked[o], tc, lut, ok, cc);
        if (!ok[pass]) continue;
        const vec3 c = cc[pass];
        const float cosv = glm::dot(glm::normalize(ranked[o].eye - w), view);
        const float wt = 1.0f / (1.0f - cosv + 1e-7f);
        sum += wt * c;
        wsum += wt;
        ++found;
      }
    color = vec3(0.0f);
    hole = found == 0;
    filled = false;
    if (!hole) {
      color = sum / wsum;
      return;
    }
    // The nearest photograph (eye distance) that saw the polygon.
    const SampleLayer* best = nullptr;
    float best_d = INFINITY;
    for (const SampleLayer& L : layers) {
      const float dd = glm::length(maps.cameras[L.photo].position - w);
      if (dd < best_d) best_d = dd, best = &L;
    }
    const int ci = int(std::floor(tc.x)), cj = int(std::floor(tc.y));
    const uint32_t best_i = best ? uint32_t(best - layers.data()) : uint32_t(layers.size());
    HoleMemo::Entry& m = memo.e[HoleMemo::slot(p, ci, cj)];
    if (options.fast && m.p == p && m.best == best_i && m.ci == ci && m.cj == cj) {
      color = m.color;
      filled = m.got;
      return;
    }
    const auto search = options.fast ? &nearest_sample : &nearest_sample_plain;
    bool got = false;
    // A texel seen only in slivers along silhouettes (no clean sample within mixed_reach texels
    // in any layer, a mixed one there): its own photographs' mixed color, nearer than any
    // clean sample the wide search below would bring from elsewhere on the polygon. Layers
    // without mixed samples (the item buffer's) never take this branch.
    if (options.mixed_reach > 0) {
      bool any_mixed = false, clean_near = false;
      for (uint32_t o = offset[p]; o < offset[p + 1]; ++o) any_mixed = any_mixed || ranked[o].layer->mixed > 0;
      vec3 unused;
      for (uint32_t o = offset[p]; any_mixed && !clean_near && o < offset[p + 1]; ++o)
        clean_near = search(*ranked[o].layer, ci, cj, options.mixed_reach, kExtrapolated, unused);
      for (uint32_t o = offset[p]; any_mixed && !clean_near && !got && o < offset[p + 1]; ++o)
        got = ranked[o].layer->mixed > 0 && search(*ranked[o].layer, ci, cj, options.mixed_reach, kMixed, color);
    }
    if (!got) got = best && search(*best, ci, cj, options.hole_radius, kExtrapolated, color);
    // Then the other photographs that saw P, closest direction first; last, the
    // mixed samples of texels no photograph saw in a pixel wholly on P.
    for (uint32_t o = offset[p]; !got && o < offset[p + 1]; ++o)
      got = search(*ranked[o].layer, ci, cj, options.hole_radius, kExtrapolated, color);
    for (uint32_t o = offset[p]; !got && o < offset[p + 1]; ++o)
      got = ranked[o].layer->mixed > 0 && search(*ranked[o].layer, ci, cj, options.hole_radius, kMixed, color);
    filled = got;
    m = {p, best_i, ci, cj, got, color};
  };

  const int W = camera.width, H = camera.height;
  nv.color = ImageF(W, H, 3, 0.0f);
  nv.unseen = ImageU8(W, H, 1, 0);
  std::vector<size_t> tile_holes, tile_filled, tile_covered;
  const int tile = 32;
  const int tiles = ((W + tile - 1) / tile) * ((H + tile - 1) / tile);
  tile_holes.assign(size_t(tiles), 0);
  tile_filled.assign(size_t(tiles), 0);
  tile_covered.assign(size_t(tiles), 0);
  const float inv_samples = 1.0f / float(ss * ss);
  parallel_for_tiles(W, H, tile, [&](const Tile& t) {
    size_t holes = 0, filled = 0, covered = 0;
    HoleMemo memo;
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) {
        // Multisampling: where all ss × ss samples see one polygon, shade once at the pixel
        // center (1/depth is affine on a plane, so its mean over the symmetric sample grid is
        // its value at the center); elsewhere shade every sample and box-average them
        // (background samples black, as the truth's black environment). The pixel is unseen
        // when any of its shaded points is a hole.
        const uint32_t p0 = polygon_at(x * ss, y * ss);
        bool uniform = p0 != kNone;
        float inv_depth = 0.0f;
        for (int sj = 0; sj < ss && uniform; ++sj)
          for (int si = 0; si < ss && uniform; ++si) {
            uniform = polygon_at(x * ss + si, y * ss + sj) == p0;
            inv_depth += 1.0f / img.depth.at(x * ss + si, y * ss + sj);
          }
        vec3 sum(0.0f);
        bool any = false, any_hole = false, all_filled = true;
        auto add = [&](uint32_t p, const vec3& w, float weight) {
          vec3 c;
          bool hole = false, got = false;
          shade(p, w, c, hole, got, memo);
          any = true;
          sum += weight * c;
          if (hole) any_hole = true, all_filled = all_filled && got;
        };
        if (uniform) {
          const float depth = ss == 1 ? img.depth.at(x, y) : float(ss * ss) / inv_depth;
          add(p0, unproject(camera, vec2(float(x) + 0.5f, float(y) + 0.5f), depth), 1.0f);
        } else {
          for (int sj = 0; sj < ss; ++sj)
            for (int si = 0; si < ss; ++si) {
              const int fx = x * ss + si, fy = y * ss + sj;
              const uint32_t p = polygon_at(fx, fy);
              if (p != kNone)
                add(p, unproject(fine, vec2(float(fx) + 0.5f, float(fy) + 0.5f), img.depth.at(fx, fy)), inv_samples);
            }
        }
        if (!any) continue;
        ++covered;
        if (any_hole) {
          ++holes;
          filled += all_filled;
          nv.unseen.at(x, y) = 1;
        }
        for (int c = 0; c < 3; ++c) nv.color.at(x, y, c) = sum[c];
      }
    tile_holes[size_t(t.index)] = holes;
    tile_filled[size_t(t.index)] = filled;
    tile_covered[size_t(t.index)] = covered;
  });
  nv.holes = std::accumulate(tile_holes.begin(), tile_holes.end(), size_t(0));
  nv.holes_filled = std::accumulate(tile_filled.begin(), tile_filled.end(), size_t(0));
  nv.covered = std::accumulate(tile_covered.begin(), tile_covered.end(), size_t(0));
  nv.blend_ms = watch.elapsed_ms();
  return nv;
}

}  // namespace proxima::gibr
