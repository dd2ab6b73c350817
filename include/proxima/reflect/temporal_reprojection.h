// Depth-based reprojection (thesis ch. 5 §5.4, step 3) of a key-frame image onto the
// reflective samples of a new frame: each sample's world point W is projected into the key
// camera and the key image is read there (bilinear over the neighbours that show the same
// reflector at the same depth, |s.d − d_proj| ≤ tolerance·d_proj, and are reliable).
// Samples with no such key pixel are disoccluded; those whose nearest key pixel is empty
// or unreliable in the image are unreliable. Both must be recomputed.
//
// With the intermediate image of warp_reflections this is the temporal method; with the
// key frame's own Lr (all reliable) it is the "direct depth reprojection" baseline, which
// reuses reflections as if they were view-independent.
#pragma once

#include <cstdint>
#include <vector>

#include "proxima/core/image.h"
#include "proxima/reflect/reflection_frame.h"
#include "proxima/reflect/temporal_depth_image.h"
#include "proxima/reflect/temporal_offset_warp.h"

namespace proxima {

enum ReuseFlag : uint8_t {
  kReuseOk = 0,
  kReuseDisoccluded = 1u << 0,  // no key pixel of the same reflector at this depth
  kReuseUnreliable = 1u << 1,   // the image is empty or unreliable there
  kReuseCurved = 1u << 2,       // with kReuseUnreliable: on a strongly curved reflector (kWarpCurved)
  kReuseEdge = 1u << 3,         // with kReuseUnreliable: on an edge of the reflected image (kWarpEdge)
  kReuseKept = 1u << 4,         // flagged, but the radiance holds the value reuse would have given
                                // (the blend-error rule's samples): its error is observed once traced
  kReuseRefined = 1u << 5,      // with kReuseUnreliable: next to a recomputed sample whose reuse
                                // value erred (TemporalOptions::refine_error)
  kReuseLearned = 1u << 6,      // with kReuseUnreliable: in a key pixel where reuse erred on an
                                // earlier frame of the key cycle (TemporalOptions::learn_error)
};

struct ReprojectOptions {
  float depth_tolerance = 0.02f;  // relative depth difference accepted as the same surface
};

inline constexpr uint32_t kNoKeyPixel = 0xFFFFFFFFu;

struct ReflectionReprojection {
  std::vector<vec3> radiance;  // per sample of the frame; 0 where flagged but under kReuseKept
  std::vector<uint8_t> flag;   // ReuseFlag bits
  std::vector<uint32_t> key_pixel;  // per sample: the key pixel it projects into (y·width + x), or
                                    // kNoKeyPixel where disoccluded
  uint64_t disoccluded = 0, unreliable = 0, curved = 0, edge = 0;  // curved, edge ⊂ unreliable
  uint64_t recompute() const { return disoccluded + unreliable; }
};

// `radiance` (3 channels) and `state` (WarpState, or null = everything reliable) are on the
// key's pixel grid. With `mesh` (the warp that made them) a reused sample reads the warped
// mesh at its exact projected position (warped_radiance_at), the bilinear mix of the image
// only where that fails. `frame` at supersample 1.
ReflectionReprojection reproject_reflections(const ReflectionFrame& frame, const ReflectionDepthImage& key,
                                             const ImageF& radiance, const ImageU8* state,
                                             const ReprojectOptions& options, const WarpedMesh* mesh = nullptr);

// The same into `out` (empty, or from an earlier call), reusing its vectors' memory: the same result.
void reproject_reflections_into(const ReflectionFrame& frame, const ReflectionDepthImage& key, const ImageF& radiance,
                                const ImageU8* state, const ReprojectOptions& options, const WarpedMesh* mesh,
                                ReflectionReprojection& out);

}  // namespace proxima
