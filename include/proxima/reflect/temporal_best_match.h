// Best reflection-pixel match (thesis ch. 5 §5.4.1, Algorithm 9): for each reflective key
// pixel s, the key pixel s* whose fitted plane (W_n, n_n) best reflects the key frame's
// reflected point R towards the new eye E_cur. The distance function of s_n is the
// Euclidean distance from E_cur to the ray from M (R mirrored in s_n's tangent plane)
// through W_n; a local descent over the 8-neighbourhood (the 3×3 hollow square) from the
// previous frame's end point finds its minimum. The offset s* − s is stored per pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "proxima/core/large_buffer.h"
#include "proxima/core/math.h"
#include "proxima/reflect/temporal_depth_image.h"

namespace proxima {

// Offset buffer O: per key pixel s* − s in key pixels (row-major), valid = 0 for INVALID
// (no match inside the reflector's silhouette, or not a reflective pixel). An INVALID
// reflective pixel keeps where its search ended, to warm-start the next frame's.
struct OffsetBuffer {
  int width = 0, height = 0;
  LargeBuffer<vec2> offset;  // whole-image buffers: on huge pages (core/large_buffer.h)
  LargeBuffer<uint8_t> valid;
};

struct BestMatchOptions {
  int max_steps = 0;              // descent steps per pixel before INVALID; 0 = width + height
  bool subpixel = true;           // refine s* by a parabola through the squared distances
                                  // of its horizontal and vertical neighbours
  float border_tolerance_px = 1.5f;  // a minimum on the silhouette border is kept only if
                                     // the reflected ray misses E_cur by ≤ this many key pixels
  bool extrapolate = false;  // with `earlier` (the offsets one frame before `previous`): also try
                             // s + 2·previous − earlier (steady motion continued) and start at
                             // whichever of the two is closer; the walks shorten as the offsets
                             // grow with the resolution
};

struct BestMatchStats {
  uint64_t searched = 0;  // reflective key pixels
  uint64_t invalid = 0;   // of those, INVALID
  uint64_t steps = 0;     // Σ descent steps
};

// Distance from `eye` to the ray from M = R mirrored in the plane (w_n, n_n) through w_n.
float match_distance(vec3 w_n, vec3 n_n, vec3 reflected, vec3 eye);

// Algorithm 9 for every reflective pixel of `key` (parallel, deterministic). `previous` (same
// size, may be null) warm-starts each search at s + its offset (valid or not) when that
// lies on the same reflector. `earlier` (may be null) is read only with options.extrapolate.
// Entries of non-reflective pixels are zero (offset 0, INVALID).
OffsetBuffer best_match_search(const ReflectionDepthImage& key, vec3 eye, const OffsetBuffer* previous,
                               const BestMatchOptions& options, BestMatchStats* stats = nullptr,
                               const OffsetBuffer* earlier = nullptr);

// best_match_search into `out`, a buffer reused from frame to frame (resized to the key's size
// if it differs): only the entries of the key's reflective pixels are written, the others keep
// what they held, so read an entry only where key.object is a reflector. Spares clearing a
// whole image per frame (the reflective pixels are ~10% of it). The same reflective entries as
// best_match_search. `out` must not be `previous` or `earlier`.
void best_match_search_into(const ReflectionDepthImage& key, vec3 eye, const OffsetBuffer* previous,
                            const BestMatchOptions& options, OffsetBuffer& out, BestMatchStats* stats = nullptr,
                            const OffsetBuffer* earlier = nullptr);

namespace detail {
// The search runs its 3×3 squares on AVX-512 (16 lanes, runtime dispatch) where the CPU has
// it, else on SSE2: the same bits. Tests set this false to compare the two paths.
extern bool best_match_wide;
bool best_match_wide_available();
}  // namespace detail

}  // namespace proxima
