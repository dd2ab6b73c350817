// Algorithm 9 (thesis ch. 5 §5.4.1): local 3×3 descent on the match distance.
#include "proxima/reflect/temporal_best_match.h"

#include <algorithm>
#include <cmath>

#include "proxima/core/image_rgb.h"
#include "proxima/core/parallel.h"

namespace proxima {

namespace {

constexpr size_t kRowGrain = 4;
// Squared distance below this fraction of its neighbours' counts as an exact match (the
// parabola would move it by < ~0.01 px).
constexpr float kExactMatch = 1e-4f;


struct Search {
  const ReflectionDepthImage& key;
  vec3 eye;
  int w, h;

  bool same(int x, int y, uint32_t object) const {
    return x >= 0 && y >= 0 && x < w && y < h && key.object.at(x, y) == object;
  }
  float distance(int x, int y, vec3 r) const {
    return match_distance(rgb_at(key.position, x, y), rgb_at(key.normal, x, y), r, eye);
  }
  // Pixels of another reflector (or none) are outside the search space.
  float distance_in(int x, int y, uint32_t object, vec3 r) const {
    return same(x, y, object) ? distance(x, y, r) : kInf;
  }
};

// Vertex of a parabola through (−1, a), (0, b), (1, c), clamped to ±0.5; 0 if not convex.
float parabola_vertex(float a, float b, float c) {
  const float denom = a - 2.0f * b + c;
  if (!(denom > 0.0f) || !std::isfinite(denom)) return 0.0f;
  return std::clamp(0.5f * (a - c) / denom, -0.5f, 0.5f);
}

}  // namespace

float match_distance(vec3 w_n, vec3 n_n, vec3 reflected, vec3 eye) {
  const vec3 m = reflected - 2.0f * glm::dot(reflected - w_n, n_n) * n_n;
  const vec3 axis = w_n - m;
  const float len = glm::length(axis);
  if (!(len > 0.0f)) return glm::length(eye - w_n);
  const vec3 dir = axis / len;
  const vec3 e = eye - m;
  const float t = glm::dot(e, dir);
  return t <= 0.0f ? glm::length(e) : glm::length(e - t * dir);
}

OffsetBuffer best_match_search(const ReflectionDepthImage& key, vec3 eye, const OffsetBuffer* previous,
                               const BestMatchOptions& options, BestMatchStats* stats,
                               const OffsetBuffer* earlier) {
  const int w = key.object.width(), h = key.object.height();
  OffsetBuffer out;
  out.width = w;
  out.height = h;
  out.offset.assign(size_t(w) * size_t(h), vec2(0.0f));
  out.valid.assign(size_t(w) * size_t(h), 0);
  const bool warm = previous && previous->width == w && previous->height == h;
  const bool extrapolate = warm && options.extrapolate && earlier && earlier->width == w && earlier->height == h;
  const int max_steps = options.max_steps > 0 ? options.max_steps : w + h;
  const float focal = focal_length_px(key.camera);
  const Search s{key, eye, w, h};
  std::vector<uint64_t> row_steps(size_t(h), 0), row_invalid(size_t(h), 0), row_searched(size_t(h), 0);

  parallel_for(size_t(h), kRowGrain, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < w; ++x) {
        const uint32_t object = key.object.at(x, y);
        if (object == kNoReflector) continue;
        ++row_searched[size_t(y)];
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        const vec3 r = key_reflected_point(key, x, y);
        int cx = x, cy = y;
        if (warm) {  // INVALID pixels too: their end point saves the next walk
          const int px = x + int(std::lround(previous->offset[i].x)), py = y + int(std::lround(previous->offset[i].y));
          if (s.same(px, py, object)) cx = px, cy = py;
        }
        float former = s.distance(cx, cy, r);
        if (extrapolate) {  // steady motion: the offset moves on by its last change
          const vec2 guess = 2.0f * previous->offset[i] - earlier->offset[i];
          const int gx = x + int(std::lround(guess.x)), gy = y + int(std::lround(guess.y));
          if ((gx != cx || gy != cy) && s.same(gx, gy, object)) {
            const float d = s.distance(gx, gy, r);
            if (d < former) former = d, cx = gx, cy = gy;
          }
        }
        bool converged = false;
        // The last step's 3×3 distances (centre included): on convergence they are the end
        // point's neighbours, which the sub-pixel fit reads again; after a step of (sx, sy)
        // the cells both squares share are not evaluated again (the same values: same bits).
        float around[3][3] = {};
        around[1][1] = former;
        int sx = 3, sy = 3;  // no previous square yet (every cell falls outside it)
        for (int step = 0; step < max_steps; ++step) {
          int bx = cx, by = cy;
          float best = kInf;
          float next[3][3];
          next[1][1] = former;
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              if (!dx && !dy) continue;
              const int ox = dx + sx, oy = dy + sy;  // the cell in the previous square
              const float d = ox >= -1 && ox <= 1 && oy >= -1 && oy <= 1
                                  ? around[oy + 1][ox + 1]
                                  : s.distance_in(cx + dx, cy + dy, object, r);
              next[dy + 1][dx + 1] = d;
              if (d < best) best = d, bx = cx + dx, by = cy + dy;
            }
          std::copy(&next[0][0], &next[0][0] + 9, &around[0][0]);
          if (!(best < former)) {  // local minimum (ties stop too: no cycles)
            converged = true;
            break;
          }
          former = best;
          sx = bx - cx;
          sy = by - cy;
          cx = bx;
          cy = by;
          ++row_steps[size_t(y)];
        }
        bool ok = converged;
        if (ok) {
          // On the silhouette border the true minimum may lie outside the reflector: keep
          // the match only if the reflected ray through W_c misses E_cur by ≤ tolerance
          // key pixels (distance scaled back to W_c by similar triangles).
          bool border = false;
          for (int dy = -1; dy <= 1 && !border; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              if (!s.same(cx + dx, cy + dy, object)) border = true;
          if (border) {
            const vec3 wc = rgb_at(key.position, cx, cy), nc = rgb_at(key.normal, cx, cy);
            const vec3 m = r - 2.0f * glm::dot(r - wc, nc) * nc;
            const float scale = glm::length(wc - m) / std::max(glm::length(eye - m), 1e-6f);
            const float miss_px = former * scale * focal / std::max(key.depth.at(cx, cy), 1e-6f);
            ok = miss_px <= options.border_tolerance_px;
          }
        }
        if (!ok) {
          ++row_invalid[size_t(y)];
          out.offset[i] = vec2(float(cx - x), float(cy - y));
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
        out.offset[i] = vec2(float(cx - x), float(cy - y)) + sub;
        out.valid[i] = 1;
      }
  });
  if (stats) {
    *stats = {};
    for (int y = 0; y < h; ++y) {
      stats->searched += row_searched[size_t(y)];
      stats->invalid += row_invalid[size_t(y)];
      stats->steps += row_steps[size_t(y)];
    }
  }
  return out;
}

}  // namespace proxima
