// `proxima bench raster` beside Mesa's llvmpipe: the optional harness proxima_llvmpipe_bench
// (bench/llvmpipe, built next to this binary when EGL/OpenGL are found) renders the frame the
// rasterizer study timed, as a separate program, at each of the study's thread counts.
#pragma once

#include <string>
#include <vector>

#include "proxima/eval/results.h"
#include "proxima/study/raster_bench.h"

namespace proxima::cli {

// The harness's ms per frame (depth + primitive id), one per timing row of the study's
// results, in row order; NaN where it is absent or failed, and the reason in `why`.
struct LlvmpipeTimes {
  std::vector<double> ms_depth_id;
  std::string why;
};

// Runs the harness on `scene` (the --scene the study loaded) with the options' camera, size
// and repetitions at the thread count of each timing row of `results` (run_raster_bench's).
LlvmpipeTimes llvmpipe_run(const std::string& scene, const study::RasterBenchStudyOptions& options,
                           const Results& results);

// Appends the columns llvmpipe_depth_id_ms and speedup_vs_llvmpipe to the timing table and
// the metrics llvmpipe_ms_depth_id and speedup_vs_llvmpipe (suffix _1t on the one-thread row
// when there are two rows); warns on stderr when the columns are left empty.
void add_llvmpipe_columns(Results& results, const LlvmpipeTimes& llvmpipe);

}  // namespace proxima::cli
