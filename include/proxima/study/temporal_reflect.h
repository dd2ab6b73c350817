// Study: temporal reuse of reflections (thesis ch. 5, reflect/temporal_reuse.h) along a
// camera path, optionally side by side with full reflection ray tracing of every frame (the
// reference, timed) and with direct depth reprojection of the same key frame
// (`proxima reflect --method temporal`, docs/temporal.md).
//
// Metrics: frames, keyframes, recompute_pct_avg, keyframe_interval_*, the step times and the
// options that shape the run; with compare: temporal_mae_* and direct_mae_* (0–255, channels
// averaged, over the reflective pixels; averaged over the frames with reflective pixels),
// speedup_vs_reference and its CPU-time twin. Tables shaped like the thesis' Tables 22–23,
// errors by key-frame age, and "Per frame" (one row per rendered frame). Images of one frame:
// temporal, recomputed_pixels; with compare reference, direct, error_temporal and
// error_direct (heat maps over the reflective pixels on the kErrorHeatmapMax scale).
#pragma once

#include <cstdint>
#include <string>

#include "proxima/core/math.h"
#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/reflect/reflection_frame.h"
#include "proxima/reflect/temporal_reuse.h"
#include "proxima/scene/scene.h"
#include "proxima/study/study.h"

namespace proxima::study {

struct TemporalReflectOptions {
  int width = 1024;        // --width: output pixels
  int height = 768;        // --height: output pixels
  std::string path;        // --path: camera path, index or name (required)
  bool compare = false;    // --compare: also full ray tracing and direct reprojection, errors and speed-up
  int light_samples = 4;   // --light-samples: n of the n×n area-light stratum centres, 1..64
  int glossy_rays = 16;    // --glossy-rays: lobe rays per glossy sample, 1..1024
  uint64_t seed = 1;       // --seed
  int frames = 0;          // --frames: frames the path is divided into; 0 = the path's own count
  int frame_step = 1;      // --frame-step: render every frame_step-th frame (reuse spans the skipped ones)
  float threshold = 0.3f;  // --threshold: key-frame threshold on the recomputed fraction, [0, 1]
  // --stretch-limit: warp triangles stretched more than this (area ratio) are unreliable.
  float stretch_limit = 16.0f;
  // --spread-limit: inf = off; e.g. 8: warp triangles on reflectors that bend neighbouring
  // reflection directions more than this many times their view angle are unreliable.
  float spread_limit = kInf;
  // --depth-discontinuity: warp corners whose s.d or s.d + s.r differ by more than this
  // fraction are not connected.
  float depth_discontinuity = 0.1f;
  // --curved-contrast: the spread limit applies only where s·Lr differs between neighbouring
  // key pixels by more than this (linear).
  float curved_contrast = 0.05f;
  // --edge-contrast: inf = off; warp triangles whose corners' s·Lr differ by more than this
  // (linear, any channel) span an edge of the reflected image and follow edge_rule.
  float edge_contrast = kInf;
  std::string edge_rule = "nearest";  // --edge-rule: there "nearest" corner's Lr, or "recompute"
  bool recompute_splats = false;      // --recompute-splats: samples no warp triangle reached are recomputed
  // --blend-error: reused samples whose expected display error (0–255) exceeds this are
  // recomputed; inf = off (the thesis' method).
  float blend_error = 8.0f;
  // --refine-error: reused neighbours of recomputed samples whose reuse value erred by more
  // than this (0–255) are recomputed too, until none is added; inf = off.
  float refine_error = kInf;
  // --learn-error: a recomputed sample whose reuse value erred by more than this (0–255)
  // marks its key pixel; later frames of the key cycle recompute samples reusing it; inf = off.
  float learn_error = kInf;
  // --keyframe-cost: TemporalOptions::keyframe_cost (rays per reflective key pixel that the
  // fixed steps cost); 0 = off (the thesis' threshold policy alone).
  float keyframe_cost = 1.0f;
  bool match_extrapolate =
      false;             // --match-extrapolate: best match also starts from the last change continued
  int image_frame = -1;  // --image-frame: frame whose images are written; −1 = the first non-key frame
  // --lobe-seed-cell: > 0 seeds glossy lobe rays per world cell of this edge × the scene
  // diagonal instead of per pixel, in the method and the reference alike; 0 = per pixel.
  float lobe_seed_cell = 0.0f;
  bool breakdown = false;  // --breakdown (needs compare): error by pixel class, key-frame age, seed noise
  // --reference-rays (needs compare): > 0: also errors against a reference with this many
  // glossy lobe rays.
  int reference_rays = 0;
};

// Throws InputError naming the flag for options out of range.
void validate(const TemporalReflectOptions& options);

// Throws InputError naming the flag when the options do not fit the scene (no such path, no
// reflective object). run_temporal_reflect checks it first; a caller may check it before
// creating the output directory.
void validate(const TemporalReflectOptions& options, const Scene& scene);

// The sampling and the reuse settings these options give (what run_temporal_reflect passes
// to prepare_reflection_frame and temporal_reflections); for callers that step frames
// themselves (the Python TemporalReflections).
ReflectionOptions reflection_options(const TemporalReflectOptions& options);
TemporalOptions temporal_options(const TemporalReflectOptions& options);

// Runs the path on the scene as loaded (animated objects posed at each frame's time and
// reused as they are), writes the images of one frame into `out`. Deterministic metrics
// (errors, counts, key frames) are the same for any thread count. `progress`, when given,
// gets one stage with a step per frame.
Results run_temporal_reflect(const Scene& scene, const TemporalReflectOptions& options,
                             const StudyOutput& out, Progress* progress = nullptr);

}  // namespace proxima::study
