// Study: reflections from screen-space clustered depth images (thesis ch. 4,
// reflect/cluster_reflection.h) on one camera or along a camera path, optionally beside
// Embree tracing the same rays and rectified environment mapping on the same rays
// (`proxima reflect --method cluster`, docs/cluster_reflections.md).
//
// Metrics: frames, reflective_pct_*, clusters_*, cluster_ms_* and the step times; with
// compare: cluster_mae_r/g/b and envmap_mae_r/g/b (0–255 per channel over the reflective
// pixels, averaged over the frames that show reflective pixels), occlusion_error_* and the
// occlusion causes, reference_ms_avg, speedup_static / speedup_dynamic. Tables shaped like the
// thesis' Tables 13–21. Images of one frame: cluster, clusters; with compare reference,
// envmap, error_cluster and error_envmap (heat maps over the reflective pixels on the
// kErrorHeatmapMax scale).
//
// With ssr (`--method ssr`): screen-space reflections (reflect/ssr_reflection.h) on the same
// frame and rays, falling back to the box-projected probe (reflect/box_probe.h) on the env
// map above; metrics ssr_ms_avg (of it ssr_depth_passes_ms_avg and ssr_trace_ms_avg, the last
// repetition's), ssr_fallback_pct_avg (reflective samples with a ray that
// fell back), ssr_fallback_rays_pct_avg, ssr_<outcome>_rays_pct_avg, ssr_steps_per_ray_avg,
// ssr_confidence_avg, boxprobe_ms_avg, and with compare ssr_mae_r/g/b, boxprobe_mae_r/g/b and
// a table beside cluster, rectified and Embree. Images ssr, ssr_fallback (red: the share a
// pixel's rays took from the fallback), with compare error_ssr, boxprobe, error_boxprobe.
#pragma once

#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/reflect/cluster_reflection.h"
#include "proxima/reflect/ssr_reflection.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/scene.h"
#include "proxima/reflect/envmap_groups.h"
#include "proxima/study/frame_split.h"
#include "proxima/study/study.h"

namespace proxima::study {

struct ClusterReflectOptions {
  int width = 512;   // --width: output pixels
  int height = 512;  // --height: output pixels
  // --camera, or --path: the path divided into `frames` frames, every `frame_step`-th
  // rendered; with --frame (frame_given) that frame of the path only.
  CameraChoice camera;
  bool frame_given = false;  // --frame was given
  bool compare = false;  // --compare: Embree on the same rays + env mapping: errors, occlusion errors, timing
  int reps = 1;          // --reps: timing repetitions per frame (medians), 1..100
  // The env-map comparison: rectified lookups on distance cube maps built per frame, one per
  // group of reflectors (--max-maps, --group-parallax; envmap_groups.h).
  EnvmapGroupOptions envmap_groups;
  int cube_size = 512;         // --cube-size: cube face side, texels
  float d_e = 0.01f;           // --d-e: rectification tolerance, meters
  float distance = 0.0f;       // --distance: search length D, meters; 0 = the scene's bounding-box diagonal
  bool edge_fallback = false;  // --edge fallback: plain lookup where the search ends beside the environment
  int frames = 0;              // --frames: frames the path is divided into; 0 = the path's own count
  int frame_step = 1;          // --frame-step: run every frame_step-th frame
  int image_frame = -1;        // --image-frame: frame whose images are written; −1 = the first one rendered
  bool full_reference =
      false;  // --full-reference: also render_reference (shadows, jittered area light, 1 bounce)
  // --ss (supersample), --gloss-rays (glossy_rays), --light-samples (area_light_samples),
  // --seed (seed).
  ReflectionOptions reflection;
  // --theta-bins, --phi-bins, --min-bin-scale, --resolution-scale, --second-layer, --march-block.
  ClusterReflectionOptions cluster;
  bool ssr = false;  // --method ssr: also SSR with the box-probe fallback on the same rays
  SsrOptions ssr_options;
};

// Throws InputError naming the flag for options out of range.
void validate(const ClusterReflectOptions& options);

// Throws InputError naming the flag when the options do not fit the scene (no such camera,
// path or frame; no reflective object). run_cluster_reflect checks it first; a caller may
// check it before creating the output directory.
void validate(const ClusterReflectOptions& options, const Scene& scene);

// Renders the frames (the scene as loaded, animated objects posed at each frame's time),
// writes the images of one frame into `out`. Deterministic metrics (errors, counts) are the
// same for any thread count. `progress`, when given, gets one stage with a step per frame.
Results run_cluster_reflect(const Scene& scene, const ClusterReflectOptions& options, const StudyOutput& out,
                            Progress* progress = nullptr);

// The run split into frame parts (study/frame_split.h) over the frames it renders (one for a
// camera; the path's, every frame_step-th, otherwise): one part's frames, their figures into
// `figures` and, when the image frame is among them, the images into `out`; and the whole
// run's metrics and tables (no images) from every part's figures concatenated in part
// order — run_cluster_reflect's, bit for bit (timings aside).
Results run_cluster_reflect_part(const Scene& scene, const ClusterReflectOptions& options, const FramePart& part,
                                 const StudyOutput& out, FrameFigures& figures, Progress* progress = nullptr);
Results cluster_reflect_results(const Scene& scene, const ClusterReflectOptions& options, const FrameFigures& figures);

}  // namespace proxima::study
