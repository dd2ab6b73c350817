// The viewer's frame rate: every viewer technique rendered headless (a ViewerSession
// without a window, overlay drawn as on screen) while the camera moves, then the
// full-resolution refine frame once it stops, optionally its error against the
// progressive reference. What `proxima bench view` runs. It has the shape of a study
// (proxima/study/study.h) but lives in viewer/, below the study layer, because it drives
// a ViewerSession.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/scene.h"
#include "proxima/study/study.h"

namespace proxima {

// The options of `proxima bench view`, one field per flag, with the flag's default.
struct ViewerBenchOptions {
  CameraChoice camera;  // --camera, --path, --frame: the start view
  int width = 640;      // --width: window width, pixels, 16..8192
  int height = 360;     // --height: window height, pixels, 16..8192
  uint64_t seed = 1;    // --seed: the techniques' sampling
  int move_scale = 2;   // --move-scale: render at 1/N of the window per side while moving,
                        // 0..16 (0 = adaptive)
  int frames = 10;      // --frames: moving frames per block, 1..10000
  int rounds = 3;       // --rounds: blocks per technique, round-robin, 1..100
  bool error = false;   // --error: also wait for each technique's reference once still (slow)
  std::vector<std::string> techniques;  // --techniques: a subset by name; empty = every
                                        // available one
};

// Throws InputError naming the flag (--width, --height, --move-scale, --frames, --rounds).
void validate(const ViewerBenchOptions& options);

// Runs the benchmark on a copy of `scene` (fly speed: a tenth of the scene diagonal per
// second; 30 frames per second of input). Per technique T: metrics T_moving_ms,
// T_moving_fps, T_refine_ms (medians), T_first_frame_ms (its warm-up frame with one-off
// builds), T_render_width, T_render_height (while moving) and with error T_error_mae; the
// table "Viewer frame rate while moving, ...". No images. Throws InputError naming
// --techniques for a technique that is not available. `progress` is not used.
Results run_viewer_bench(const Scene& scene, const ViewerBenchOptions& options, const study::StudyOutput& out,
                         Progress* progress = nullptr);

}  // namespace proxima
