// Internals of the rasterizer (rasterizer.h): the binned frame that the geometry stage
// (src/raster/rasterizer.cpp) builds, and the per-tile coverage loop, a template so that
// the fragment test is inlined. Not a public interface.
//
// Fixed point "20.12": screen positions in units of 1/4096 pixel (kSubpixelBits = 12),
// int32. The guard band keeps |x|, |y| < 2^15 pixels, so positions fit in 28 bits, edge
// deltas in 29 bits and edge function values E = dx·(py − ya) − dy·(px − xa) (units
// 1/4096² px²) in 59 bits: exact in int64. (8 bits, the hardware norm, left 0.1% of the
// pixels of a 290k-triangle scene disagreeing with Embree on edges; 12 bits: 0.01%.)
#pragma once

#include <algorithm>
#include <concepts>
#include <cstdint>
#include <memory>
#include <vector>

#include "proxima/core/timer.h"

namespace proxima {
namespace raster_detail {

inline constexpr int kTileSize = 64;      // pixels per side of a raster tile
inline constexpr int kSubpixelBits = 12;  // 20.12 fixed point
inline constexpr int kSubpixel = 1 << kSubpixelBits;
static_assert(kTileSize <= 64, "a row run's keep mask is one uint64_t");

// One screen triangle ready for coverage (a clipped triangle gives several).
struct Setup {
  int32_t x[3], y[3];      // 20.12 vertex positions, ordered so the signed area is > 0
  int32_t x0, y0, x1, y1;  // inclusive range of pixels whose centers the bbox holds,
                           // clamped to the viewport
  uint32_t triangle;
  // Planes over pixel offsets (fx, fy) = (x − x0, y − y0):
  //   value = p[0] + p[2]·fy + p[1]·fx   (evaluated in this order)
  float z[3];  // 1/W (W = view depth)
  float u[3];  // u/W with u the Embree barycentric of the scene triangle
  float v[3];  // v/W
};

// Triangles of one fixed-size slice of the draw list, binned by tile.
struct Chunk {
  std::vector<Setup> setups;
  std::vector<uint32_t> offsets;  // tile t holds binned[offsets[t] .. offsets[t+1])
  std::vector<uint32_t> binned;   // setup indices, grouped by tile, in draw order
  uint64_t submitted = 0, culled = 0, clipped = 0;
};

// A scene vertex in clip space: X/W, Y/W are continuous pixel coordinates, W = −z_cam.
struct ClipVertex {
  float X, Y, W;
  int32_t fx, fy;  // 20.12 snapped X/W, Y/W; valid only when no clip bit is set
  uint32_t code;   // outcode bits (rasterizer.cpp)
};

// A contiguous run of the draw list: triangle ids first .. first+count−1, or, with an
// id list, list positions. `start` is the run's position in the whole draw list.
struct DrawRun {
  uint32_t first, count;
  uint64_t start;
};

struct TileCounts {
  uint64_t tested = 0, written = 0;
};

struct Frame {
  const Scene* scene = nullptr;
  int width = 0, height = 0;
  int tiles_x = 0, tiles_y = 0;
  uint32_t outputs = 0;
  bool direct_light = false;
  bool needs_uv = false;
  vec3 camera_position{0.0f};
  std::vector<ClipVertex> vertices;  // by scene vertex index; only drawn objects' are set
  std::vector<DrawRun> runs;
  const uint32_t* id_list = nullptr;  // RasterOptions::triangles, or null
  std::vector<uint8_t> object_visible;  // per object: 0 not drawn, 1 drawn, 2 culled
  std::vector<Chunk> chunks;  // the first chunk_count are this frame's
  size_t chunk_count = 0;
  std::vector<TileCounts> tile_counts;
  uint64_t objects_drawn = 0, objects_culled = 0;
  double geometry_ms = 0.0;
  Stopwatch raster_clock;
};

// Frames are pooled so their buffers are reused across calls (no page faults per frame).
struct FrameReturn {
  void operator()(Frame* frame) const;
};
using FrameLease = std::unique_ptr<Frame, FrameReturn>;

// Per-tile depth / id / barycentric buffers, row-major kTileSize × kTileSize, cleared
// to empty (+inf, kNoTriangle); u, v only with barycentrics.
struct TileBuffer {
  TileBuffer(bool with_uv);
  std::vector<float> depth;
  std::vector<uint32_t> id;
  std::vector<float> u, v;
};

FrameLease prepare_frame(const Scene& scene, const Camera& camera, const RasterOptions& options,
                         RasterImages& out);
void resolve_tile(const Frame& frame, const Tile& tile, const TileBuffer& buffer, RasterImages& out);
RasterStats finish_frame(const Frame& frame);

// The pixels [begin, end) of a row that a setup covers: one run, since each edge function
// is linear in x; the scan stops after it. e: edge values at x0; step: per pixel.
// Out of line on purpose: inlined into a tile loop whose fragment test calls a function
// (NRR), the compiler kept the edge values and steps on the stack and this scan ran
// several times slower than in the conventional instantiation.
[[gnu::noinline]] inline void row_run(const int64_t* e, const int64_t* step, int x0, int x1, int& begin,
                                      int& end) {
  int64_t e0 = e[0], e1 = e[1], e2 = e[2];
  const int64_t s0 = step[0], s1 = step[1], s2 = step[2];
  int x = x0;
  while (x <= x1 && (e0 | e1 | e2) < 0) {
    ++x;
    e0 += s0;
    e1 += s1;
    e2 += s2;
  }
  begin = x;
  while (x <= x1 && (e0 | e1 | e2) >= 0) {
    ++x;
    e0 += s0;
    e1 += s1;
    e2 += s2;
  }
  end = x;
}

// Edge i runs from vertex i to vertex i+1; inside is E ≥ 0 (area > 0). Top-left fill
// rule (y down): a center exactly on an edge belongs to the triangle only if the edge
// is a top edge (horizontal, pointing +x) or a left edge (pointing −y); the −1 bias
// turns "E > 0" into "E ≥ 0" for the others. e: values at the center of pixel (x0, y0);
// step_x, step_y: per pixel right and down.
inline void edge_functions(const Setup& s, int x0, int y0, int64_t* e, int64_t* step_x, int64_t* step_y) {
  const int64_t px = int64_t(x0) * kSubpixel + kSubpixel / 2;
  const int64_t py = int64_t(y0) * kSubpixel + kSubpixel / 2;
  for (int i = 0; i < 3; ++i) {
    const int j = i == 2 ? 0 : i + 1;
    const int64_t dx = int64_t(s.x[j]) - s.x[i], dy = int64_t(s.y[j]) - s.y[i];
    const bool top_left = dy < 0 || (dy == 0 && dx > 0);
    e[i] = dx * (py - s.y[i]) - dy * (px - s.x[i]) - (top_left ? 0 : 1);
    step_x[i] = -dy * kSubpixel;
    step_y[i] = dx * kSubpixel;
  }
}

// A fragment test that can also take one row run of a setup at once:
// keep_run(fragments, n) → bit k set keeps fragments[k]; n ≤ kTileSize, the fragments are
// one triangle's, in one row, left to right, each past the depth test. Used instead of
// the per-fragment call when the depth test is on (rasterizer.h, Fragment tests).
template <typename Test>
concept RunFragmentTest = requires(Test& test, const Fragment* fragments, int n) {
  { test.keep_run(fragments, n) } -> std::convertible_to<uint64_t>;
};

// A fragment test that can also say, per triangle, that it keeps every fragment of it:
// keeps_all(triangle) → true; the rasterizer then skips the test for that triangle's
// fragments (rasterizer.h, Fragment tests).
template <typename Test>
concept TriangleKeepsAllTest = requires(Test& test, uint32_t triangle) {
  { test.keeps_all(triangle) } -> std::convertible_to<bool>;
};

// Coverage of one setup inside one tile.
template <bool kDepthTest, bool kUV, typename Test>
inline void raster_setup(const Setup& s, const Tile& tile, TileBuffer& buf, Test& test, TileCounts& counts) {
  if constexpr (TriangleKeepsAllTest<Test>) {
    if (test.keeps_all(s.triangle)) {
      AcceptAllFragments all;
      raster_setup<kDepthTest, kUV>(s, tile, buf, all, counts);
      return;
    }
  }
  const int x0 = std::max(s.x0, tile.x0), x1 = std::min(s.x1, tile.x1 - 1);
  const int y0 = std::max(s.y0, tile.y0), y1 = std::min(s.y1, tile.y1 - 1);
  if (x0 > x1 || y0 > y1) return;

  int64_t e[3], step_x[3], step_y[3];
  edge_functions(s, x0, y0, e, step_x, step_y);

  for (int y = y0; y <= y1; ++y) {
    int begin, end;
    row_run(e, step_x, x0, x1, begin, end);
    const float fy = float(y - s.y0);
    const float z_row = s.z[0] + s.z[2] * fy;
    const size_t row = size_t(y - tile.y0) * kTileSize;
    float* depth_row = buf.depth.data() + row;
    uint32_t* id_row = buf.id.data() + row;
    if constexpr (kDepthTest && RunFragmentTest<Test>) {
      // The same fragments, tested and written as below, but the test sees the run's
      // depth-passing fragments at once (its pixels are distinct, so no write in the run
      // changes another fragment's depth test or the per-pixel call order).
      Fragment run[kTileSize];
      int n = 0;
      for (int x = begin; x < end; ++x) {
        const int tx = x - tile.x0;
        const float fx = float(x - s.x0);
        const float depth = 1.0f / (z_row + s.z[1] * fx);
        const float held = depth_row[tx];
        if (!(depth < held || (depth == held && s.triangle < id_row[tx]))) continue;
        Fragment& f = run[n++];
        f = Fragment{x, y, s.triangle, depth, 0.0f, 0.0f};
        if constexpr (kUV) {
          f.u = (s.u[0] + s.u[2] * fy + s.u[1] * fx) * depth;
          f.v = (s.v[0] + s.v[2] * fy + s.v[1] * fx) * depth;
        }
      }
      if (n > 0) {
        counts.tested += uint64_t(n);
        const uint64_t keep = test.keep_run(static_cast<const Fragment*>(run), n);
        for (int k = 0; k < n; ++k) {
          if (!((keep >> k) & 1u)) continue;
          ++counts.written;
          const int tx = run[k].x - tile.x0;
          depth_row[tx] = run[k].depth;
          id_row[tx] = s.triangle;
          if constexpr (kUV) {
            buf.u[row + size_t(tx)] = run[k].u;
            buf.v[row + size_t(tx)] = run[k].v;
          }
        }
      }
      e[0] += step_y[0];
      e[1] += step_y[1];
      e[2] += step_y[2];
      continue;
    }
    for (int x = begin; x < end; ++x) {
      const int tx = x - tile.x0;
      const float fx = float(x - s.x0);
      const float depth = 1.0f / (z_row + s.z[1] * fx);
      if constexpr (kDepthTest) {
        const float held = depth_row[tx];
        if (!(depth < held || (depth == held && s.triangle < id_row[tx]))) continue;
      }
      Fragment f{x, y, s.triangle, depth, 0.0f, 0.0f};
      if constexpr (kUV) {
        f.u = (s.u[0] + s.u[2] * fy + s.u[1] * fx) * depth;
        f.v = (s.v[0] + s.v[2] * fy + s.v[1] * fx) * depth;
      }
      ++counts.tested;
      if (!test(static_cast<const Fragment&>(f))) continue;
      ++counts.written;
      depth_row[tx] = depth;
      id_row[tx] = s.triangle;
      if constexpr (kUV) {
        buf.u[row + size_t(tx)] = f.u;
        buf.v[row + size_t(tx)] = f.v;
      }
    }
    e[0] += step_y[0];
    e[1] += step_y[1];
    e[2] += step_y[2];
  }
}

// A fragment test that reads per-triangle data it can fetch ahead: prefetch(triangle) is
// a hint only (it must not change what the test answers).
template <typename Test>
concept PrefetchingTest = requires(Test& test, uint32_t triangle) { test.prefetch(triangle); };

// All binned setups of one tile, chunk by chunk: draw order. A tile reads a sparse subset
// of each chunk's setups, and with millions of small triangles every one is a cache miss:
// the setup kAhead bins ahead is fetched early, and the per-triangle data of the test for
// the one kAhead/2 ahead (hints only, the same bits).
template <bool kDepthTest, bool kUV, typename Test>
void raster_tile(Frame& frame, const Tile& tile, TileBuffer& buf, Test& test) {
  constexpr uint32_t kAhead = 8;
  const size_t t = size_t(tile.y0 / kTileSize) * size_t(frame.tiles_x) + size_t(tile.x0 / kTileSize);
  TileCounts counts;
  for (size_t c = 0; c < frame.chunk_count; ++c) {
    const Chunk& chunk = frame.chunks[c];
    const uint32_t end = chunk.offsets[t + 1];
    for (uint32_t k = chunk.offsets[t]; k < end; ++k) {
      if (k + kAhead < end) {
        const char* ahead = reinterpret_cast<const char*>(&chunk.setups[chunk.binned[k + kAhead]]);
        __builtin_prefetch(ahead);
        __builtin_prefetch(ahead + sizeof(Setup) - 1);
      }
      if constexpr (PrefetchingTest<Test>)
        if (k + kAhead / 2 < end) test.prefetch(chunk.setups[chunk.binned[k + kAhead / 2]].triangle);
      raster_setup<kDepthTest, kUV>(chunk.setups[chunk.binned[k]], tile, buf, test, counts);
    }
  }
  frame.tile_counts[t] = counts;
}

}  // namespace raster_detail

template <typename FragmentTest>
RasterStats rasterize(const Scene& scene, const Camera& camera, const RasterOptions& options,
                      RasterImages& out, FragmentTest&& test) {
  raster_detail::FrameLease lease = raster_detail::prepare_frame(scene, camera, options, out);
  raster_detail::Frame& frame = *lease;
  parallel_for_tiles(camera.width, camera.height, raster_detail::kTileSize, [&](const Tile& tile) {
    raster_detail::TileBuffer buffer(frame.needs_uv);
    if (options.depth_test) {
      if (frame.needs_uv)
        raster_detail::raster_tile<true, true>(frame, tile, buffer, test);
      else
        raster_detail::raster_tile<true, false>(frame, tile, buffer, test);
    } else {
      if (frame.needs_uv)
        raster_detail::raster_tile<false, true>(frame, tile, buffer, test);
      else
        raster_detail::raster_tile<false, false>(frame, tile, buffer, test);
    }
    raster_detail::resolve_tile(frame, tile, buffer, out);
  });
  return raster_detail::finish_frame(frame);
}

}  // namespace proxima
