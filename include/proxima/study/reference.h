// The reference render (DESIGN.md "Reference = ground truth"): the Embree ray-traced image
// of a scene from one camera, with its primary-visibility buffers (depth, normal, triangle
// id) and the time of each step. What `proxima render` runs.
#pragma once

#include <cstddef>
#include <cstdint>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/scene.h"
#include "proxima/study/study.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::study {

// The options of `proxima render`, one field per flag, with the flag's default.
struct ReferenceStudyOptions {
  CameraChoice camera;     // --camera, --path, --frame
  int width = 512;         // --width, pixels
  int height = 512;        // --height, pixels
  uint64_t seed = 1;       // --seed: the sub-sample and light-sample streams
  int supersample = 1;     // --spp k: k×k stratified samples per pixel, 1..64
  int light_samples = 4;   // --light-samples n: n×n samples per area light, 1..64
  int glossy_rays = 16;    // --glossy-rays: rays per glossy lobe, 1..4096
  int bounces = 2;         // --bounces: reflection depth, 0..16 (0 = no reflections)
  float time = -1.0f;      // --time, seconds: pose of animated scenes; < 0 = the --path
                           // frame's time, or 0 without a path
};

// Throws InputError naming the flag (--spp, --light-samples, --glossy-rays, --bounces).
void validate(const ReferenceStudyOptions& options);

// The renderer's options these give (sampling and seed).
ReferenceOptions reference_options(const ReferenceStudyOptions& options);

// One reference render and the times of its steps.
struct ReferenceRender {
  Camera camera;
  size_t triangles = 0;       // of the posed scene
  ImageF color;               // linear RGB
  ItemBuffer item;            // empty unless asked for
  double bvh_build_ms = 0.0;  // Embree BVH of the posed scene
  double item_buffer_ms = 0.0;
  double render_ms = 0.0;
};

// Poses `scene` at the options' time (animated scenes only), builds its BVH, traces the
// item buffer when `item_buffer` is set, then renders the reference. Deterministic for any
// thread count but for the times. Throws InputError for invalid options or camera choice.
ReferenceRender render_reference_view(const Scene& scene, const ReferenceStudyOptions& options, bool item_buffer);

// Runs the study. Metrics: bvh_build_ms, item_buffer_ms, render_ms, coverage_pct (pixels
// whose primary ray hits the scene). Table "render <scene>": triangles, width, height, spp
// (samples per pixel, k²), bvh_build_ms, render_ms. Images: color (color.png, sRGB),
// color_linear (color.exr), depth (depth.exr), normal (normal.exr), triangle_id (id.exr:
// ids as float, −1 where nothing was hit). `progress` is not used (one step of a caller's
// bar).
Results run_reference(const Scene& scene, const ReferenceStudyOptions& options, const StudyOutput& out,
                      Progress* progress = nullptr);

}  // namespace proxima::study
