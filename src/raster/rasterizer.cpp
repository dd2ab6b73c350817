// Tiled half-space rasterizer (rasterizer.h).
//
// Follows the structure of hardware and of Mesa's llvmpipe: a geometry stage (transform,
// homogeneous clipping, triangle setup, binning to screen tiles) then a raster stage per
// tile. Coverage uses fixed-point edge functions with the top-left rule as in
// J. Pineda, "A Parallel Algorithm for Polygon Rasterization", SIGGRAPH 1988, and
// N. Capens, "Advanced Rasterization", 2004 (also the model of meshoptimizer's
// src/rasterizer.cpp); clipping is Sutherland–Hodgman in homogeneous clip space
// (Blinn & Newell, "Clipping Using Homogeneous Coordinates", SIGGRAPH 1978) against the
// near and far planes and a guard band, so the viewport sides never clip.
//
// Determinism: the draw list is cut into fixed-size chunks (independent of the thread
// count); each chunk's setups and bins depend only on its triangles, and each tile walks
// the chunks in order, so every pixel sees its fragments in draw order.
#include "proxima/raster/rasterizer.h"
#include "proxima/raster/depth_raster.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <mutex>

#include "proxima/core/error.h"
#include "proxima/scene/shading.h"

namespace proxima {
namespace raster_detail {
namespace {

// Triangles per chunk of the draw list, vertices per chunk of the vertex transform.
constexpr uint64_t kChunkTriangles = 4096;
constexpr uint64_t kChunkVertices = 16384;

// Guard band, pixels beyond each viewport side. With kMaxImageSide = 16384 every snapped
// position stays inside (−2^15, 2^15) pixels, the 20.12 range of raster_frame.h.
constexpr float kGuardBandPx = 8000.0f;
static_assert(kMaxImageSide + 8000 < (1 << 15));

// Outcode bits. Viewport bits reject a triangle when all three vertices share one;
// clip bits send it through homogeneous clipping.
enum : uint32_t {
  kOutLeft = 1u << 0,     // X < 0
  kOutRight = 1u << 1,    // X > width·W
  kOutTop = 1u << 2,      // Y < 0
  kOutBottom = 1u << 3,   // Y > height·W
  kOutNear = 1u << 4,     // W < near   (also a clip plane)
  kOutFar = 1u << 5,      // W > far    (also a clip plane)
  kGuardLeft = 1u << 6,   // X < −G·W
  kGuardRight = 1u << 7,  // X > (width + G)·W
  kGuardTop = 1u << 8,
  kGuardBottom = 1u << 9,
  kNotFinite = 1u << 10,  // NaN or infinite clip coordinates: the triangle is dropped
};
constexpr uint32_t kRejectMask = kOutLeft | kOutRight | kOutTop | kOutBottom | kOutNear | kOutFar;
constexpr uint32_t kClipMask = kOutNear | kOutFar | kGuardLeft | kGuardRight | kGuardTop | kGuardBottom;

struct ClipSpace {
  // Rows of the world → clip transform: X = f·x_c + (w/2)·W, Y = −f·y_c + (h/2)·W,
  // W = −z_cam (so X/W, Y/W are continuous pixel coordinates).
  vec4 row_x, row_y, row_w;
  float width, height, near, far;

  uint32_t outcode(float X, float Y, float W) const {
    uint32_t c = 0;
    if (X < 0.0f) c |= kOutLeft;
    if (X > width * W) c |= kOutRight;
    if (Y < 0.0f) c |= kOutTop;
    if (Y > height * W) c |= kOutBottom;
    if (W < near) c |= kOutNear;
    if (W > far) c |= kOutFar;
    if (X < -kGuardBandPx * W) c |= kGuardLeft;
    if (X > (width + kGuardBandPx) * W) c |= kGuardRight;
    if (Y < -kGuardBandPx * W) c |= kGuardTop;
    if (Y > (height + kGuardBandPx) * W) c |= kGuardBottom;
    return c;
  }
};

ClipSpace make_clip_space(const Camera& camera) {
  const glm::dmat4 view(view_matrix(camera));  // world → camera, column-major
  const double f = focal_length_px(camera);
  auto row = [&](int r) { return glm::dvec4(view[0][r], view[1][r], view[2][r], view[3][r]); };
  const glm::dvec4 w = -row(2);
  ClipSpace cs;
  cs.row_x = vec4(f * row(0) + 0.5 * camera.width * w);
  cs.row_y = vec4(-f * row(1) + 0.5 * camera.height * w);
  cs.row_w = vec4(w);
  cs.width = float(camera.width);
  cs.height = float(camera.height);
  cs.near = camera.near;
  cs.far = camera.far;
  return cs;
}

// 20.12 snapping of a continuous pixel coordinate (round to nearest even), in double.
// Shared by the vertex stage and the clipper so a vertex snaps identically in every
// triangle using it.
inline int32_t snap(double clip, double w) { return int32_t(std::lrint((clip / w) * kSubpixel)); }

// A vertex during setup: snapped position, 1/W and the scene triangle's barycentrics.
struct SetupVertex {
  int32_t x, y;
  float iw, u, v;
};

// The pixels whose centers (kSubpixel·x + kSubpixel/2) lie in the snapped triangle's
// bounding box, clamped to the image; x0 > x1 or y0 > y1 when there are none.
struct PixelBox {
  int x0, y0, x1, y1;
  bool empty() const { return x0 > x1 || y0 > y1; }
};
[[gnu::always_inline]] inline PixelBox pixel_box(const SetupVertex& a, const SetupVertex& b, const SetupVertex& c, int width, int height) {
  const int32_t min_x = std::min({a.x, b.x, c.x}), max_x = std::max({a.x, b.x, c.x});
  const int32_t min_y = std::min({a.y, b.y, c.y}), max_y = std::max({a.y, b.y, c.y});
  return {std::max((min_x - kSubpixel / 2 + kSubpixel - 1) >> kSubpixelBits, 0),
          std::max((min_y - kSubpixel / 2 + kSubpixel - 1) >> kSubpixelBits, 0),
          std::min((max_x - kSubpixel / 2) >> kSubpixelBits, width - 1),
          std::min((max_y - kSubpixel / 2) >> kSubpixelBits, height - 1)};
}

// The common start of a triangle's setup: false when it is degenerate after snapping or
// culled as a back face, or covers no pixel center's bbox; else b and c swapped if needed
// so that the triangle is counter-clockwise on screen, its vertices in `s` and its pixel
// box in `box`.
bool orient_and_bound(SetupVertex& a, SetupVertex& b, SetupVertex& c, bool cull_back, int width, int height,
                      Setup& s, PixelBox& box) {
  const int64_t area2 =
      (int64_t(b.x) - a.x) * (int64_t(c.y) - a.y) - (int64_t(b.y) - a.y) * (int64_t(c.x) - a.x);
  // With y down, a counter-clockwise (front) scene triangle has area2 < 0.
  if (area2 == 0 || (cull_back && area2 > 0)) return false;
  if (area2 < 0) std::swap(b, c);
  box = pixel_box(a, b, c, width, height);
  if (box.empty()) return false;
  const SetupVertex* v[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    s.x[i] = v[i]->x;
    s.y[i] = v[i]->y;
  }
  return true;
}

// Screen-space plane (value, d/dx, d/dy) of a quantity given at the snapped vertices
// (q0, q1, q2), through them by Cramer's rule in double, referenced to the center of pixel
// (x0, y0).
void screen_plane(const SetupVertex& a, const SetupVertex& b, const SetupVertex& c, int x0, int y0, double q0,
                  double q1, double q2, float* p) {
  const double inv_scale = 1.0 / kSubpixel;
  const double x10 = (b.x - a.x) * inv_scale, y10 = (b.y - a.y) * inv_scale;
  const double x20 = (c.x - a.x) * inv_scale, y20 = (c.y - a.y) * inv_scale;
  const double inv_det = 1.0 / (x10 * y20 - x20 * y10);
  const double ox = (x0 + 0.5) - a.x * inv_scale, oy = (y0 + 0.5) - a.y * inv_scale;
  const double d1 = q1 - q0, d2 = q2 - q0;
  const double gx = (d1 * y20 - d2 * y10) * inv_det;
  const double gy = (d2 * x10 - d1 * x20) * inv_det;
  p[0] = float(q0 + gx * ox + gy * oy);
  p[1] = float(gx);
  p[2] = float(gy);
}

// Setup of one screen triangle; false when it covers no pixel center's bbox, is
// degenerate after snapping, or is culled as a back face.
bool emit_setup(SetupVertex a, SetupVertex b, SetupVertex c, uint32_t triangle, bool cull_back, bool with_uv,
                int width, int height, std::vector<Setup>& out) {
  Setup s;
  PixelBox box;
  if (!orient_and_bound(a, b, c, cull_back, width, height, s, box)) return false;
  s.x0 = box.x0;
  s.y0 = box.y0;
  s.x1 = box.x1;
  s.y1 = box.y1;
  s.triangle = triangle;

  // Screen-space planes of 1/W, u/W, v/W.
  screen_plane(a, b, c, s.x0, s.y0, a.iw, b.iw, c.iw, s.z);
  if (with_uv) {
    screen_plane(a, b, c, s.x0, s.y0, double(a.u) * a.iw, double(b.u) * b.iw, double(c.u) * c.iw, s.u);
    screen_plane(a, b, c, s.x0, s.y0, double(a.v) * a.iw, double(b.v) * b.iw, double(c.v) * c.iw, s.v);
  }
  out.push_back(s);
  return true;
}

// Homogeneous clip-space polygon vertex with the scene triangle's barycentrics. Double:
// a vertex cut at the near plane has a small W, and X/W would amplify float cancellation
// in X beyond the 1/4096-pixel grid.
struct PolyVertex {
  double X, Y, W, u, v;
};

// Signed distance to clip plane `bit` (≥ 0 inside).
double plane_distance(const ClipSpace& cs, uint32_t bit, const PolyVertex& p) {
  switch (bit) {
    case kOutNear:
      return p.W - cs.near;
    case kOutFar:
      return cs.far - p.W;
    case kGuardLeft:
      return p.X + kGuardBandPx * p.W;
    case kGuardRight:
      return (double(cs.width) + kGuardBandPx) * p.W - p.X;
    case kGuardTop:
      return p.Y + kGuardBandPx * p.W;
    default:
      return (double(cs.height) + kGuardBandPx) * p.W - p.Y;  // kGuardBottom
  }
}

// Sutherland–Hodgman against the planes in `planes`; returns the vertex count (≤ 9).
// Intersections are always computed from the inside vertex towards the outside one, so a
// shared edge is cut at the same point in both triangles (no cracks).
int clip_polygon(const ClipSpace& cs, uint32_t planes, PolyVertex* poly, int n) {
  PolyVertex tmp[9];
  for (uint32_t bit : {kOutNear, kOutFar, kGuardLeft, kGuardRight, kGuardTop, kGuardBottom}) {
    if (!(planes & bit) || n == 0) continue;
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const PolyVertex& p = poly[i];
      const PolyVertex& q = poly[(i + 1) % n];
      const double dp = plane_distance(cs, bit, p), dq = plane_distance(cs, bit, q);
      if (dp >= 0.0) tmp[m++] = p;
      if ((dp >= 0.0) != (dq >= 0.0)) {
        const PolyVertex& in = dp >= 0.0 ? p : q;
        const PolyVertex& out = dp >= 0.0 ? q : p;
        const double d_in = dp >= 0.0 ? dp : dq, d_out = dp >= 0.0 ? dq : dp;
        const double t = d_in / (d_in - d_out);
        tmp[m++] = {in.X + t * (out.X - in.X), in.Y + t * (out.Y - in.Y), in.W + t * (out.W - in.W),
                    in.u + t * (out.u - in.u), in.v + t * (out.v - in.v)};
      }
    }
    n = m;
    std::copy(tmp, tmp + n, poly);
  }
  return n;
}

// World bounds in the frustum? Conservative: false only when all 8 corners lie outside
// one frustum plane.
bool bounds_visible(const ClipSpace& cs, const Bounds3& b) {
  if (b.empty()) return false;
  uint32_t all = ~0u;
  for (int i = 0; i < 8; ++i) {
    const vec4 p((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z, 1.0f);
    all &= cs.outcode(glm::dot(cs.row_x, p), glm::dot(cs.row_y, p), glm::dot(cs.row_w, p));
  }
  return (all & kRejectMask) == 0;
}

// One scene vertex to clip space with its outcode and (unclipped) snapped position.
ClipVertex clip_vertex(const ClipSpace& cs, vec3 position) {
  const vec4 p(position, 1.0f);
  ClipVertex v;
  v.X = glm::dot(cs.row_x, p);
  v.Y = glm::dot(cs.row_y, p);
  v.W = glm::dot(cs.row_w, p);
  const bool finite = std::isfinite(v.X) && std::isfinite(v.Y) && std::isfinite(v.W);
  v.code = finite ? cs.outcode(v.X, v.Y, v.W) : kNotFinite;
  v.fx = v.fy = 0;
  if (!(v.code & kClipMask)) {
    v.fx = snap(v.X, v.W);
    v.fy = snap(v.Y, v.W);
  }
  return v;
}

enum class TriangleFate { Culled, Emitted, Clipped, ClippedAway };

// Rejection, clipping and setup of one scene triangle into `out` (one setup, or one per
// fan triangle of its clipped polygon).
TriangleFate setup_triangle(const ClipSpace& cs, const ClipVertex& v0, const ClipVertex& v1, const ClipVertex& v2,
                            uint32_t triangle, bool cull_back, bool with_uv, int width, int height,
                            std::vector<Setup>& out) {
  const ClipVertex* v[3] = {&v0, &v1, &v2};
  if (v[0]->code & v[1]->code & v[2]->code & kRejectMask) return TriangleFate::Culled;
  if ((v[0]->code | v[1]->code | v[2]->code) & kNotFinite) return TriangleFate::Culled;
  const uint32_t any = (v[0]->code | v[1]->code | v[2]->code) & kClipMask;
  if (!any) {
    const SetupVertex a{v[0]->fx, v[0]->fy, 1.0f / v[0]->W, 0.0f, 0.0f};
    const SetupVertex b{v[1]->fx, v[1]->fy, 1.0f / v[1]->W, 1.0f, 0.0f};
    const SetupVertex c{v[2]->fx, v[2]->fy, 1.0f / v[2]->W, 0.0f, 1.0f};
    return emit_setup(a, b, c, triangle, cull_back, with_uv, width, height, out) ? TriangleFate::Emitted
                                                                                 : TriangleFate::Culled;
  }
  PolyVertex poly[9] = {{v[0]->X, v[0]->Y, v[0]->W, 0.0f, 0.0f},
                        {v[1]->X, v[1]->Y, v[1]->W, 1.0f, 0.0f},
                        {v[2]->X, v[2]->Y, v[2]->W, 0.0f, 1.0f}};
  const int n = clip_polygon(cs, any, poly, 3);
  SetupVertex sv[9];
  for (int i = 0; i < n; ++i)
    sv[i] = {snap(poly[i].X, poly[i].W), snap(poly[i].Y, poly[i].W), float(1.0 / poly[i].W), float(poly[i].u),
             float(poly[i].v)};
  bool emitted = false;
  for (int i = 1; i + 1 < n; ++i)
    emitted |= emit_setup(sv[0], sv[i], sv[i + 1], triangle, cull_back, with_uv, width, height, out);
  return emitted ? TriangleFate::Clipped : TriangleFate::ClippedAway;
}

// Coverage of one setup over the whole image, keeping each pixel's greatest 1/W: the
// fragments of raster_setup (raster_frame.h) without the tile, the ids or the fragment
// test. Its depth 1/(1/W) is monotonic in 1/W, so the least depth is 1 / (greatest 1/W),
// taken once per pixel at the end instead of one division per fragment.
void depth_setup(const Setup& s, float* inv_depth, int width) {
  int64_t e[3], step_x[3], step_y[3];
  edge_functions(s, s.x0, s.y0, e, step_x, step_y);
  for (int y = s.y0; y <= s.y1; ++y) {
    int begin, end;
    row_run(e, step_x, s.x0, s.x1, begin, end);
    const float fy = float(y - s.y0);
    const float z_row = s.z[0] + s.z[2] * fy;
    float* row = inv_depth + size_t(y) * size_t(width);
    for (int x = begin; x < end; ++x) row[x] = std::max(row[x], z_row + s.z[1] * float(x - s.x0));
    e[0] += step_y[0];
    e[1] += step_y[1];
    e[2] += step_y[2];
  }
}

// Whether `mask` holds a texel of `box` (not empty).
bool any_texel(const TexelMask& mask, const PixelBox& box) {
  const int first = box.x0 >> 6, last = box.x1 >> 6;
  const uint64_t head = ~uint64_t(0) << (box.x0 & 63), tail = ~uint64_t(0) >> (63 - (box.x1 & 63));
  for (int y = box.y0; y <= box.y1; ++y) {
    const uint64_t* row = mask.bits.data() + size_t(y) * size_t(mask.words_per_row);
    for (int i = first; i <= last; ++i) {
      uint64_t word = row[i];
      if (i == first) word &= head;
      if (i == last) word &= tail;
      if (word) return true;
    }
  }
  return false;
}

// An unclipped triangle straight into the depth-only image, keeping each pixel's greatest
// 1/W: the setup of emit_setup and the fragments of depth_setup with the same arithmetic
// (same bits), but without building a Setup, with the row scan inlined, and with the 1/W
// plane (double, one division) computed only once a pixel center is covered — a triangle
// of about one texel often covers none. Returns whether emit_setup would emit a setup.
bool depth_triangle(SetupVertex a, SetupVertex b, SetupVertex c, bool cull_back, int width, int height,
                    float* inv_depth) {
  Setup s;
  PixelBox box;
  if (!orient_and_bound(a, b, c, cull_back, width, height, s, box)) return false;
  const int x0 = box.x0, y0 = box.y0, x1 = box.x1;
  int64_t e[3], step_x[3], step_y[3];
  edge_functions(s, x0, y0, e, step_x, step_y);
  bool have_plane = false;
  float z[3] = {0.0f, 0.0f, 0.0f};  // the 1/W plane, once a pixel center is covered
  for (int y = y0; y <= box.y1; ++y) {
    int64_t e0 = e[0], e1 = e[1], e2 = e[2];
    int x = x0;
    while (x <= x1 && (e0 | e1 | e2) < 0) {
      ++x;
      e0 += step_x[0];
      e1 += step_x[1];
      e2 += step_x[2];
    }
    const int begin = x;
    while (x <= x1 && (e0 | e1 | e2) >= 0) {
      ++x;
      e0 += step_x[0];
      e1 += step_x[1];
      e2 += step_x[2];
    }
    const int end = x;
    if (begin < end) {
      if (!have_plane) {
        screen_plane(a, b, c, x0, y0, a.iw, b.iw, c.iw, z);
        have_plane = true;
      }
      const float z_row = z[0] + z[2] * float(y - y0);
      float* row = inv_depth + size_t(y) * size_t(width);
      for (int px = begin; px < end; ++px) row[px] = std::max(row[px], z_row + z[1] * float(px - x0));
    }
    e[0] += step_y[0];
    e[1] += step_y[1];
    e[2] += step_y[2];
  }
  return true;
}

// Triangle setup and binning for draw-list positions [begin, end).
void build_chunk(const Frame& frame, const ClipSpace& cs, bool cull_back, uint64_t begin, uint64_t end,
                 Chunk& chunk) {
  const Scene& scene = *frame.scene;
  chunk.setups.clear();
  chunk.submitted = chunk.culled = chunk.clipped = 0;
  const auto& runs = frame.runs;
  size_t r = size_t(std::upper_bound(runs.begin(), runs.end(), begin,
                                     [](uint64_t pos, const DrawRun& run) { return pos < run.start; }) -
                    runs.begin()) -
             1;
  // An id list (a sorted draw order) jumps around the scene's triangles and vertices, and
  // at millions of triangles each jump misses the caches: fetch the index triple
  // 2·kAhead positions ahead and that triangle's clip vertices kAhead ahead (hints only:
  // the same arithmetic, the same bits). Without a list the accesses are sequential.
  constexpr uint64_t kAhead = 16;
  const uint64_t list_size = frame.id_list ? runs.back().start + runs.back().count : 0;
  for (uint64_t pos = begin; pos < end; ++pos) {
    while (pos >= runs[r].start + runs[r].count) ++r;
    const uint32_t item = runs[r].first + uint32_t(pos - runs[r].start);
    const uint32_t triangle = frame.id_list ? frame.id_list[item] : item;
    if (frame.id_list) {
      if (pos + 2 * kAhead < list_size) {
        const uint32_t far = frame.id_list[pos + 2 * kAhead];
        __builtin_prefetch(&scene.triangles[far]);
        if (!scene.objects.empty()) __builtin_prefetch(&scene.triangle_object[far]);
      }
      if (pos + kAhead < list_size) {
        const uvec3 ahead = scene.triangles[frame.id_list[pos + kAhead]];
        __builtin_prefetch(&frame.vertices[ahead.x]);
        __builtin_prefetch(&frame.vertices[ahead.y]);
        __builtin_prefetch(&frame.vertices[ahead.z]);
      }
    }
    if (frame.id_list && !scene.objects.empty() && frame.object_visible[scene.triangle_object[triangle]] != 1)
      continue;
    ++chunk.submitted;
    const uvec3 idx = scene.triangles[triangle];
    const TriangleFate fate = setup_triangle(cs, frame.vertices[idx.x], frame.vertices[idx.y], frame.vertices[idx.z],
                                             triangle, cull_back, frame.needs_uv, frame.width, frame.height,
                                             chunk.setups);
    chunk.culled += fate == TriangleFate::Culled;
    chunk.clipped += fate != TriangleFate::Emitted && fate != TriangleFate::Culled;
    chunk.culled += fate == TriangleFate::ClippedAway;
  }

  // Counting sort of (tile, setup) pairs by tile; setup order is kept within a tile.
  const size_t tiles = size_t(frame.tiles_x) * size_t(frame.tiles_y);
  chunk.offsets.assign(tiles + 1, 0);
  for (const Setup& s : chunk.setups)
    for (int ty = s.y0 / kTileSize; ty <= s.y1 / kTileSize; ++ty)
      for (int tx = s.x0 / kTileSize; tx <= s.x1 / kTileSize; ++tx)
        ++chunk.offsets[size_t(ty) * size_t(frame.tiles_x) + size_t(tx) + 1];
  for (size_t t = 0; t < tiles; ++t) chunk.offsets[t + 1] += chunk.offsets[t];
  chunk.binned.resize(chunk.offsets[tiles]);
  std::vector<uint32_t> cursor(chunk.offsets.begin(), chunk.offsets.end() - 1);
  for (uint32_t k = 0; k < chunk.setups.size(); ++k) {
    const Setup& s = chunk.setups[k];
    for (int ty = s.y0 / kTileSize; ty <= s.y1 / kTileSize; ++ty)
      for (int tx = s.x0 / kTileSize; tx <= s.x1 / kTileSize; ++tx)
        chunk.binned[cursor[size_t(ty) * size_t(frame.tiles_x) + size_t(tx)]++] = k;
  }
}

template <typename T>
void ensure_image(Image<T>& image, int width, int height, int channels) {
  if (image.width() != width || image.height() != height || image.channels() != channels)
    image = Image<T>(width, height, channels);
}

std::mutex g_pool_mutex;
std::vector<std::unique_ptr<Frame>> g_pool;

}  // namespace

void FrameReturn::operator()(Frame* frame) const {
  std::lock_guard<std::mutex> lock(g_pool_mutex);
  g_pool.emplace_back(frame);
}

TileBuffer::TileBuffer(bool with_uv)
    : depth(size_t(kTileSize) * kTileSize, kInf), id(size_t(kTileSize) * kTileSize, kNoTriangle) {
  if (with_uv) {
    u.assign(depth.size(), 0.0f);
    v.assign(depth.size(), 0.0f);
  }
}

FrameLease prepare_frame(const Scene& scene, const Camera& camera, const RasterOptions& options,
                         RasterImages& out) {
  validate_camera(camera, "rasterizer camera");
  assert(int(!options.objects.empty()) + int(!options.triangles.empty()) + int(!options.triangle_runs.empty()) <= 1);
  assert(options.triangle_runs.empty() || !scene.objects.empty());
  assert(options.object_bounds.empty() || options.object_bounds.size() == scene.objects.size());
  Stopwatch clock;

  FrameLease frame;
  {
    std::lock_guard<std::mutex> lock(g_pool_mutex);
    if (!g_pool.empty()) {
      frame.reset(g_pool.back().release());
      g_pool.pop_back();
    }
  }
  if (!frame) frame.reset(new Frame);
  Frame& f = *frame;
  f.scene = &scene;
  f.width = camera.width;
  f.height = camera.height;
  f.tiles_x = (camera.width + kTileSize - 1) / kTileSize;
  f.tiles_y = (camera.height + kTileSize - 1) / kTileSize;
  f.outputs = options.outputs;
  f.direct_light = options.direct_light;
  f.needs_uv = options.fragment_barycentrics ||
               (options.outputs & (kRasterBarycentric | kRasterNormal | kRasterDiffuse));
  f.camera_position = camera.position;
  f.tile_counts.assign(size_t(f.tiles_x) * size_t(f.tiles_y), TileCounts{});
  f.objects_drawn = f.objects_culled = 0;

  const int w = camera.width, h = camera.height;
  if (options.outputs & kRasterDepth) ensure_image(out.depth, w, h, 1);
  if (options.outputs & kRasterTriangle) ensure_image(out.triangle, w, h, 1);
  if (options.outputs & kRasterBarycentric) ensure_image(out.barycentric, w, h, 2);
  if (options.outputs & kRasterNormal) ensure_image(out.normal, w, h, 3);
  if (options.outputs & kRasterDiffuse) ensure_image(out.diffuse, w, h, 3);
  if (options.outputs & kRasterObject) ensure_image(out.object, w, h, 1);

  const ClipSpace cs = make_clip_space(camera);

  // Objects to draw, culled against the frustum by their bounds. A scene without objects
  // is drawn as one unculled object.
  const uint32_t object_count = uint32_t(scene.objects.size());
  std::vector<uint32_t> drawn;
  f.object_visible.assign(std::max<size_t>(object_count, 1), 0);
  // Each object once, however often the list names it (an id list names it per triangle).
  auto consider = [&](uint32_t o) {
    assert(o < object_count);
    if (f.object_visible[o]) return;
    const Bounds3 b = options.object_bounds.empty() ? object_bounds(scene, o) : options.object_bounds[o];
    if (bounds_visible(cs, b)) {
      f.object_visible[o] = 1;
      drawn.push_back(o);
    } else {
      f.object_visible[o] = 2;
      ++f.objects_culled;
    }
  };
  if (object_count == 0) {
    // nothing to cull
  } else if (!options.objects.empty()) {
    for (uint32_t o : options.objects) consider(o);
  } else if (!options.triangles.empty()) {
    for (uint32_t t : options.triangles) consider(scene.triangle_object[t]);
  } else if (!options.triangle_runs.empty()) {
    for (const TriangleRun& run : options.triangle_runs)
      if (run.count > 0) consider(scene.triangle_object[run.first]);
  } else {
    for (uint32_t o = 0; o < object_count; ++o) consider(o);
  }
  f.objects_drawn = drawn.size();

  // Vertex stage: the drawn objects' vertices to clip space, outcodes, snapped positions.
  f.vertices.resize(scene.positions.size());
  std::vector<DrawRun> vertex_runs;
  uint64_t vertex_total = 0;
  auto add_vertex_run = [&](uint32_t first, uint32_t count) {
    vertex_runs.push_back({first, count, vertex_total});
    vertex_total += count;
  };
  if (object_count == 0) {
    add_vertex_run(0, uint32_t(scene.positions.size()));
  } else if (!options.triangle_runs.empty()) {
    // The drawn runs' vertex ranges, sorted and merged so that no vertex is transformed
    // twice (neighbouring runs share vertices).
    std::vector<std::pair<uint32_t, uint32_t>> ranges;  // [begin, end)
    for (const TriangleRun& run : options.triangle_runs)
      if (run.count > 0 && run.vertex_count > 0 && f.object_visible[scene.triangle_object[run.first]] == 1)
        ranges.emplace_back(run.first_vertex, run.first_vertex + run.vertex_count);
    std::sort(ranges.begin(), ranges.end());
    for (size_t i = 0; i < ranges.size();) {
      const uint32_t begin = ranges[i].first;
      uint32_t end = ranges[i].second;
      for (++i; i < ranges.size() && ranges[i].first <= end; ++i) end = std::max(end, ranges[i].second);
      add_vertex_run(begin, end - begin);
    }
  } else {
    for (uint32_t o : drawn) add_vertex_run(scene.objects[o].first_vertex, scene.objects[o].vertex_count);
  }
  const size_t vertex_chunks = size_t((vertex_total + kChunkVertices - 1) / kChunkVertices);
  parallel_for(vertex_chunks, 1, [&](size_t c0, size_t c1) {
    for (size_t c = c0; c < c1; ++c) {
      const uint64_t begin = c * kChunkVertices, end = std::min(begin + kChunkVertices, vertex_total);
      size_t r = size_t(std::upper_bound(vertex_runs.begin(), vertex_runs.end(), begin,
                                         [](uint64_t pos, const DrawRun& run) { return pos < run.start; }) -
                        vertex_runs.begin()) -
                 1;
      for (uint64_t pos = begin; pos < end; ++pos) {
        while (pos >= vertex_runs[r].start + vertex_runs[r].count) ++r;
        const uint32_t i = vertex_runs[r].first + uint32_t(pos - vertex_runs[r].start);
        f.vertices[i] = clip_vertex(cs, scene.positions[i]);
      }
    }
  });

  // Draw list: the drawn objects' triangle ranges, or the id list.
  f.runs.clear();
  f.id_list = nullptr;
  uint64_t total = 0;
  if (!options.triangles.empty()) {
    f.id_list = options.triangles.data();
    f.runs.push_back({0, uint32_t(options.triangles.size()), 0});
    total = options.triangles.size();
  } else if (object_count == 0) {
    f.runs.push_back({0, uint32_t(scene.triangles.size()), 0});
    total = scene.triangles.size();
  } else if (!options.triangle_runs.empty()) {
    // The runs of drawn objects, consecutive ones joined.
    for (const TriangleRun& run : options.triangle_runs) {
      if (run.count == 0 || f.object_visible[scene.triangle_object[run.first]] != 1) continue;
      if (!f.runs.empty() && f.runs.back().first + f.runs.back().count == run.first)
        f.runs.back().count += run.count;
      else
        f.runs.push_back({run.first, run.count, total});
      total += run.count;
    }
  } else {
    for (uint32_t o : drawn) {
      const Object& obj = scene.objects[o];
      if (obj.triangle_count == 0) continue;
      f.runs.push_back({obj.first_triangle, obj.triangle_count, total});
      total += obj.triangle_count;
    }
  }

  // Setup and binning, chunk by chunk.
  f.chunk_count = size_t((total + kChunkTriangles - 1) / kChunkTriangles);
  if (f.chunks.size() < f.chunk_count) f.chunks.resize(f.chunk_count);
  const bool cull_back = options.cull == CullMode::Back;
  parallel_for(f.chunk_count, 1, [&](size_t c0, size_t c1) {
    for (size_t c = c0; c < c1; ++c)
      build_chunk(f, cs, cull_back, c * kChunkTriangles, std::min((c + 1) * kChunkTriangles, total),
                  f.chunks[c]);
  });

  f.geometry_ms = clock.elapsed_ms();
  f.raster_clock.restart();
  return frame;
}

namespace {

// What the resolve needs of one triangle, loaded once per run of pixels showing it.
struct TriangleAttributes {
  uint32_t id = kNoTriangle;
  vec3 p[3]{}, n[3]{};
  vec2 uv[3]{};
  vec3 ng{0.0f};  // unit geometric normal turned towards the camera
  const Material* material = nullptr;
  const Texture* texture = nullptr;

  void load(const Scene& scene, uint32_t t, vec3 eye) {
    id = t;
    const uvec3 idx = scene.triangles[t];
    for (int k = 0; k < 3; ++k) {
      p[k] = scene.positions[idx[k]];
      n[k] = scene.normals[idx[k]];
      uv[k] = scene.uvs[idx[k]];
    }
    // The camera is on one side of the triangle's plane for all its points.
    ng = triangle_normal(scene, t);
    if (glm::dot(ng, p[0] - eye) > 0.0f) ng = -ng;
    material = &scene.materials[scene.triangle_material[t]];
    texture = material->diffuse_texture >= 0 ? &scene.textures[size_t(material->diffuse_texture)] : nullptr;
  }
};

}  // namespace

// Normals follow the reference renderer (trace/): the interpolated vertex normal, turned
// into the hemisphere of the geometric normal that faces the camera.
void resolve_tile(const Frame& frame, const Tile& tile, const TileBuffer& buffer, RasterImages& out) {
  const Scene& scene = *frame.scene;
  const uint32_t outputs = frame.outputs;
  const vec3 eye = frame.camera_position;
  const int span = tile.x1 - tile.x0;
  TriangleAttributes tri;
  for (int y = tile.y0; y < tile.y1; ++y) {
    const size_t row = size_t(y - tile.y0) * kTileSize;
    if (outputs & kRasterDepth) std::copy_n(&buffer.depth[row], span, &out.depth.at(tile.x0, y));
    if (outputs & kRasterTriangle) std::copy_n(&buffer.id[row], span, &out.triangle.at(tile.x0, y));
    if (!(outputs & (kRasterObject | kRasterBarycentric | kRasterNormal | kRasterDiffuse))) continue;
    uint32_t* object_row = outputs & kRasterObject ? &out.object.at(tile.x0, y) : nullptr;
    float* bary_row = outputs & kRasterBarycentric ? &out.barycentric.at(tile.x0, y) : nullptr;
    float* normal_row = outputs & kRasterNormal ? &out.normal.at(tile.x0, y) : nullptr;
    float* diffuse_row = outputs & kRasterDiffuse ? &out.diffuse.at(tile.x0, y) : nullptr;
    for (int k = 0; k < span; ++k) {
      const size_t i = row + size_t(k);
      const uint32_t t = buffer.id[i];
      if (object_row) object_row[k] = t == kNoTriangle ? kNoObject : scene.triangle_object[t];
      // The tile holds (u, v) only when an output needs them (not for objects alone).
      const bool uv = t != kNoTriangle && !buffer.u.empty();
      const float u = uv ? buffer.u[i] : 0.0f;
      const float v = uv ? buffer.v[i] : 0.0f;
      if (bary_row) {
        bary_row[2 * k] = u;
        bary_row[2 * k + 1] = v;
      }
      if (!normal_row && !diffuse_row) continue;
      vec3 normal(0.0f), color(0.0f);
      if (t != kNoTriangle) {
        if (tri.id != t) tri.load(scene, t, eye);
        const float w = 1.0f - u - v;
        normal = w * tri.n[0] + u * tri.n[1] + v * tri.n[2];
        const float len = glm::length(normal);
        normal = len > 0.0f ? normal / len : tri.ng;
        if (glm::dot(normal, tri.ng) < 0.0f) normal = -normal;
        if (diffuse_row) {
          const vec3 albedo =
              tri.texture ? tri.material->diffuse *
                                sample_texture(*tri.texture, w * tri.uv[0] + u * tri.uv[1] + v * tri.uv[2])
                          : tri.material->diffuse;
          color = albedo;
          if (frame.direct_light) {
            // docs/shading.md without shadows and reflections (scene/shading.h).
            ShadingTerms terms;
            terms.emission = tri.material->emission;
            terms.ambient = scene.ambient;
            terms.albedo = albedo;
            terms.specular = tri.material->specular;
            const vec3 p = w * tri.p[0] + u * tri.p[1] + v * tri.p[2];
            for (const PointLight& light : scene.point_lights)
              terms.direct_irradiance += point_light_irradiance(light, p, normal);
            color = combine_shading(terms);
          }
        }
      }
      if (normal_row)
        for (int c = 0; c < 3; ++c) normal_row[3 * k + c] = normal[c];
      if (diffuse_row)
        for (int c = 0; c < 3; ++c) diffuse_row[3 * k + c] = color[c];
    }
  }
}

RasterStats finish_frame(const Frame& frame) {
  RasterStats stats;
  stats.objects_drawn = frame.objects_drawn;
  stats.objects_culled = frame.objects_culled;
  for (size_t c = 0; c < frame.chunk_count; ++c) {
    const Chunk& chunk = frame.chunks[c];
    stats.triangles_submitted += chunk.submitted;
    stats.triangles_culled += chunk.culled;
    stats.triangles_clipped += chunk.clipped;
    stats.triangles_rasterized += chunk.setups.size();
  }
  for (const TileCounts& t : frame.tile_counts) {
    stats.fragments_tested += t.tested;
    stats.fragments_written += t.written;
  }
  stats.geometry_ms = frame.geometry_ms;
  stats.raster_ms = frame.raster_clock.elapsed_ms();
  return stats;
}

}  // namespace raster_detail

std::vector<Bounds3> raster_object_bounds(const Scene& scene) {
  std::vector<Bounds3> bounds(scene.objects.size());
  parallel_for(bounds.size(), 1, [&](size_t b, size_t e) {
    for (size_t o = b; o < e; ++o) bounds[o] = object_bounds(scene, uint32_t(o));
  });
  return bounds;
}

RasterImages rasterize(const Scene& scene, const Camera& camera, const RasterOptions& options,
                       RasterStats* stats) {
  RasterImages images;
  const RasterStats s = rasterize(scene, camera, options, images, AcceptAllFragments{});
  if (stats) *stats = s;
  return images;
}

}  // namespace proxima

namespace proxima {

void TexelMask::reset(int width, int height) {
  words_per_row = (width + 63) / 64;
  bits.assign(size_t(words_per_row) * size_t(height), 0);
}

RasterStats rasterize_depth_serial(const Scene& scene, const Camera& camera, std::span<const Bounds3> bounds,
                                   CullMode cull, ImageF& depth, DepthRasterScratch& scratch) {
  return rasterize_depth_serial(scene, camera, bounds, cull, nullptr, depth, scratch);
}

RasterStats rasterize_depth_serial(const Scene& scene, const Camera& camera, std::span<const Bounds3> bounds,
                                   CullMode cull, const TexelMask* needed, ImageF& depth, DepthRasterScratch& scratch) {
  using namespace raster_detail;
  validate_camera(camera, "rasterizer camera");
  if (needed && (needed->words_per_row != (camera.width + 63) / 64 ||
                 needed->bits.size() != size_t(needed->words_per_row) * size_t(camera.height)))
    fail_input("texel mask: size differs from the image's");
  assert(bounds.empty() || bounds.size() == scene.objects.size());
  const int w = camera.width, h = camera.height;
  ensure_image(depth, w, h, 1);
  std::fill(depth.data().begin(), depth.data().end(), 0.0f);  // 1/W; 1/0 = +inf: empty
  const ClipSpace cs = make_clip_space(camera);
  const bool cull_back = cull == CullMode::Back;
  scratch.vertices.resize(scene.positions.size());
  RasterStats stats;
  float* image = depth.data().data();
  // One object's triangles (a scene without objects is one unculled object).
  auto draw = [&](uint32_t first_vertex, uint32_t vertex_count, uint32_t first_triangle, uint32_t triangle_count) {
    for (uint32_t i = first_vertex; i < first_vertex + vertex_count; ++i)
      scratch.vertices[i] = clip_vertex(cs, scene.positions[i]);
    stats.triangles_submitted += triangle_count;
    for (uint32_t t = first_triangle; t < first_triangle + triangle_count; ++t) {
      const uvec3 idx = scene.triangles[t];
      const ClipVertex &v0 = scratch.vertices[idx.x], &v1 = scratch.vertices[idx.y], &v2 = scratch.vertices[idx.z];
      if (!((v0.code | v1.code | v2.code) & (kClipMask | kNotFinite))) {
        bool rejected = v0.code & v1.code & v2.code & kRejectMask;
        if (needed && !rejected) {
          const PixelBox box = pixel_box({v0.fx, v0.fy, 0.0f, 0.0f, 0.0f}, {v1.fx, v1.fy, 0.0f, 0.0f, 0.0f},
                                         {v2.fx, v2.fy, 0.0f, 0.0f, 0.0f}, w, h);
          rejected = box.empty() || !any_texel(*needed, box);
        }
        const bool drawn = !rejected && depth_triangle({v0.fx, v0.fy, 1.0f / v0.W, 0.0f, 0.0f},
                                                       {v1.fx, v1.fy, 1.0f / v1.W, 0.0f, 0.0f},
                                                       {v2.fx, v2.fy, 1.0f / v2.W, 0.0f, 0.0f}, cull_back, w, h, image);
        stats.triangles_culled += !drawn;
        stats.triangles_rasterized += drawn;
        continue;
      }
      scratch.setups.clear();
      const TriangleFate fate = setup_triangle(cs, v0, v1, v2, t, cull_back, false, w, h, scratch.setups);
      stats.triangles_culled += fate == TriangleFate::Culled || fate == TriangleFate::ClippedAway;
      stats.triangles_clipped += fate == TriangleFate::Clipped || fate == TriangleFate::ClippedAway;
      stats.triangles_rasterized += scratch.setups.size();
      for (const Setup& s : scratch.setups) depth_setup(s, image, w);
    }
  };
  if (scene.objects.empty()) {
    draw(0, uint32_t(scene.positions.size()), 0, uint32_t(scene.triangles.size()));
    stats.objects_drawn = 1;
  }
  for (uint32_t o = 0; o < uint32_t(scene.objects.size()); ++o) {
    const Object& obj = scene.objects[o];
    if (!bounds_visible(cs, bounds.empty() ? object_bounds(scene, o) : bounds[o])) {
      ++stats.objects_culled;
      continue;
    }
    ++stats.objects_drawn;
    draw(obj.first_vertex, obj.vertex_count, obj.first_triangle, obj.triangle_count);
  }
  for (float& d : depth.data()) d = 1.0f / d;
  return stats;
}

}  // namespace proxima
