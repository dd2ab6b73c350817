// The software rasterizer against Embree: its triangle-id agreement with ray-cast item
// buffers on every built-in camera, and its frame time on one scene at one thread and at all
// threads. What `proxima bench raster` runs; the command adds Mesa's llvmpipe beside the
// times (an optional OpenGL harness, a separate program: apps/proxima/llvmpipe_columns.h).
#pragma once

#include <cstddef>
#include <vector>

#include "proxima/core/progress.h"
#include "proxima/eval/raster_agreement.h"
#include "proxima/eval/results.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/scene.h"
#include "proxima/study/study.h"

namespace proxima::study {

// The options of `proxima bench raster`, one field per flag, with the flag's default.
struct RasterBenchStudyOptions {
  CameraChoice camera;          // --camera, --path, --frame
  int width = 1024;             // --width, pixels
  int height = 1024;            // --height, pixels
  int threads = 0;              // --threads: the "all threads" count (≤ 0 = all cores); 1 is timed too
  int reps = 9;                 // --reps: timed frames per measurement, 1..1000 (median reported)
  bool skip_agreement = false;  // --skip-agreement: time only
};

// Throws InputError naming the flag (--reps).
void validate(const RasterBenchStudyOptions& options);

// The agreement of every built-in camera at size × size, and its worst cases.
struct AgreementSummary {
  std::vector<CameraAgreement> cameras;  // registry order
  double min_agreement_pct = 100.0;      // lowest agreement_pct over the cameras
  double min_with_ties_pct = 100.0;      // lowest agreement_with_ties_pct
  size_t other = 0;                      // Σ disagreements that are no tie
};
AgreementSummary agreement_summary(int size);

// Runs the study. Without skip_agreement: metrics id_agreement_pct,
// id_agreement_with_ties_pct, id_disagreements_other and the table "rasterized vs
// ray-cast triangle ids, 512×512, every built-in camera". Then per thread count (suffix _1t
// for 1 thread when all threads > 1): raster_ms_depth_id, raster_ms_gbuffer, tris_per_s, and
// the table "raster <scene>, WxH, median of N" (columns threads, depth_id_ms, gbuffer_ms,
// tris_per_s; one row per thread count, all threads last). No images. Throws InputError for
// invalid options or camera choice.
Results run_raster_bench(const Scene& scene, const RasterBenchStudyOptions& options, const StudyOutput& out,
                         Progress* progress = nullptr);

}  // namespace proxima::study
