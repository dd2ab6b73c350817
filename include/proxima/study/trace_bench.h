// The Embree reference's speed: BVH build time and closest-hit rays per second for the
// primary rays of a camera and the mirror rays from their hits on reflective surfaces, at
// one thread and at all threads, medians over repetitions. What `proxima bench trace` runs.
#pragma once

#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/scene.h"
#include "proxima/study/study.h"

namespace proxima::study {

// The options of `proxima bench trace`, one field per flag, with the flag's default.
struct TraceBenchOptions {
  CameraChoice camera;  // --camera, --path, --frame
  int width = 1024;     // --width, pixels: one primary ray per pixel
  int height = 1024;    // --height, pixels
  int threads = 0;      // --threads: the "all threads" count (≤ 0 = all cores); 1 is timed too
  int reps = 5;         // --reps: repetitions per measurement, 1..1000 (median reported)
};

// Throws InputError naming the flag (--reps).
void validate(const TraceBenchOptions& options);

// Runs the study. Metrics at all threads: bvh_build_ms, primary_mrays_s, reflection_mrays_s
// (millions of rays per second; 0 without reflection rays); the same with suffix _1t at one
// thread (absent when all threads = 1); reflection_rays, triangles. Table "bench trace:
// <scene>, WxH, median of N": threads, bvh_build_ms, primary_mrays_s, reflection_mrays_s.
// No images. Throws InputError for invalid options or camera choice.
Results run_trace_bench(const Scene& scene, const TraceBenchOptions& options, const StudyOutput& out,
                        Progress* progress = nullptr);

}  // namespace proxima::study
