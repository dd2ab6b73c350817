// Temporal reuse of reflections between frames (thesis ch. 5, Algorithm 8). Per frame, on
// a ReflectionFrame at one sample per pixel (its G-buffer pass is the diffuse shading):
// a key frame traces every reflection ray with Embree and stores the reflection depth
// image; any other frame runs best match → offset warp → depth reprojection and traces
// only the disoccluded and unreliable samples. The result composes as base + s·Lr
// (compose_reflections), the same blend full ray tracing uses (docs/temporal.md).
// Key-frame policy (§5.4.4): when a frame recomputes more than `keyframe_threshold` of its
// reflective samples, the next frame is a key frame (samples on strongly curved reflectors,
// reflected edges or detail between key samples, recomputed whatever the key frame, do not
// count).
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "proxima/reflect/reflection_frame.h"
#include "proxima/reflect/temporal_best_match.h"
#include "proxima/reflect/temporal_depth_image.h"
#include "proxima/reflect/temporal_offset_warp.h"
#include "proxima/reflect/temporal_reprojection.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

struct TemporalOptions {
  BestMatchOptions match;
  WarpOptions warp;
  ReprojectOptions reproject;
  float keyframe_threshold = 0.3f;  // stale_fraction above which the next frame is a key frame
  // Not in the thesis: the cost rule (docs/temporal.md) also starts a key frame once a reuse
  // frame's work reaches the average work per frame since the last key frame — from then on
  // a new cycle is cheaper on average. Work counts traced rays, and the fixed steps (best
  // match, warp, reprojection) as this many rays per reflective key pixel; 0 = off.
  float keyframe_cost = 0.0f;
  // Not in the thesis: feedback from observed error (docs/temporal.md). A recomputed sample
  // whose reuse value was kept (kReuseKept: the blend-error rule's, and those added below)
  // shows, once traced, that value's display error (0–255, any channel, as blend_risk).
  // Above refine_error its reused 8-neighbours on the same reflector are recomputed too, and
  // observed in turn, round after round until none is added; inf = off.
  float refine_error = kInf;
  // Above learn_error the key pixel the sample projects into is marked for the rest of the
  // key cycle; later frames recompute (and observe) the reused samples projecting into a
  // marked key pixel before reusing them; inf = off.
  float learn_error = kInf;
};

// What persists between frames.
struct TemporalState {
  ReflectionDepthImage key;
  OffsetBuffer previous;   // last frame's offsets (warm start) when warm_frames ≥ 1
  OffsetBuffer earlier;    // the frame's before those (BestMatchOptions::extrapolate) when warm_frames ≥ 2
  OffsetBuffer spare;      // the oldest offsets, recycled as the next frame's (best_match_search_into)
  int warm_frames = 0;     // reuse frames since the key frame whose offsets are kept; the three
                           // buffers keep their memory across key frames (no fresh pages)
  IntermediateReflection warp;  // the last warp: its buffers are reused by the next
  // Buffers reused frame to frame (fresh large allocations cost page faults):
  TracedReflections traced;             // the last key frame's trace
  ReflectionReprojection reprojection;  // the last reprojection (its vectors swap with the caller's)
  std::vector<uint32_t> todo;           // the samples the last frame recomputed
  // Feedback from observed error (refine_error, learn_error):
  std::vector<uint8_t> marked;          // per key pixel: reuse erred there in this key cycle
  uint64_t marked_serial = 0;           // the key frame (ReflectionDepthImage::serial) `marked` is of
  std::vector<uint32_t> sample_at;      // per G-buffer pixel, its sample, or none
  std::vector<std::pair<uint32_t, vec3>> observed, next;  // samples with their reuse values
  bool need_key = true;    // the next frame is a key frame
  int frames_since_key = 0;
  double cycle_work = 0.0;  // Σ work / full-trace work of the frames since the key frame, it included
};

struct TemporalFrameStats {
  bool key = false;
  uint64_t reflective = 0;   // reflective samples of the frame
  uint64_t recomputed = 0;   // traced on a non-key frame (disoccluded + unreliable)
  uint64_t rays = 0, traced_rays = 0;  // the frame's reflection rays; of those, traced (all on a key frame)
  double work = 0.0;         // the frame's work over a full trace's (TemporalOptions::keyframe_cost)
  uint64_t disoccluded = 0, unreliable = 0, invalid_offsets = 0;
  uint64_t curved = 0;       // of the unreliable: on a strongly curved reflector (kReuseCurved)
  uint64_t edge = 0;         // of the unreliable: on an edge of the reflected image (kReuseEdge)
  uint64_t refined = 0;      // of the unreliable: neighbours of observed errors (kReuseRefined)
  uint64_t learned = 0;      // of the unreliable: in key pixels marked by observed errors (kReuseLearned)
  uint64_t observed = 0;     // recomputed samples whose reuse error was observed (feedback on)
  uint64_t refine_rounds = 0;  // refinement rounds that added samples
  uint64_t match_steps = 0;  // Σ best-match descent steps
  double key_ms = 0.0;        // key frame: full trace + reflection depth image
  double match_ms = 0.0;      // best match (Algorithm 9)
  double warp_ms = 0.0;       // reflection offset (grid forward warp)
  double reproject_ms = 0.0;  // depth-based reprojection
  double recompute_ms = 0.0;  // tracing the flagged samples
  double reflection_ms() const { return key_ms + match_ms + warp_ms + reproject_ms + recompute_ms; }
  double recompute_fraction() const { return reflective ? double(recomputed) / double(reflective) : 0.0; }
  // What a new key frame would save: the recomputed samples bar the curved, edge, refined
  // and learned ones: reflected edges and detail between key samples are there whatever the
  // key frame.
  double stale_fraction() const {
    return reflective ? double(recomputed - curved - edge - refined - learned) / double(reflective) : 0.0;
  }
};

// Reflected radiance per sample of `frame` (supersample 1; `rays` built from `scene`).
// Updates `state` and applies the key-frame policy. `flags` (may be null) receives the
// ReuseFlag of every sample (all kReuseOk on a key frame). Deterministic for any thread count.
std::vector<vec3> temporal_reflections(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                                       TemporalState& state, const TemporalOptions& options,
                                       TemporalFrameStats* stats = nullptr, std::vector<uint8_t>* flags = nullptr);

// The same into `radiance` (resized to the frame's samples). Its memory and that of `flags`
// are swapped with buffers kept in `state`: a caller that passes the same vectors every
// frame allocates nothing once sizes settle.
void temporal_reflections_into(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                               TemporalState& state, const TemporalOptions& options, std::vector<vec3>& radiance,
                               TemporalFrameStats* stats = nullptr, std::vector<uint8_t>* flags = nullptr);

// The baseline: the current key frame's Lr reprojected by depth alone; flagged samples are
// traced, like the temporal method's. `recomputed` (may be null) receives their count.
std::vector<vec3> direct_reprojection(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                                      const ReflectionDepthImage& key, const ReprojectOptions& options,
                                      uint64_t* recomputed = nullptr);

}  // namespace proxima
