// `proxima reflect --method temporal` (issue 8, thesis ch. 5): temporal reuse of reflections
// along a camera path, optionally side by side with full reflection ray tracing and the
// direct depth reprojection baseline (--compare).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "command.h"
#include "proxima/core/math.h"

namespace proxima::cli {

// Flags only the temporal method has; `proxima reflect` owns the shared ones.
struct TemporalReflectFlags {
  int frames = 0;               // frames the path is divided into; 0 = the path's own count
  int frame_step = 1;           // render every frame_step-th frame (reuse spans the skipped ones)
  float threshold = 0.3f;       // key-frame threshold on the recomputed fraction
  float stretch_limit = 16.0f;  // warp triangles stretched more than this in area are unreliable
  float spread_limit = kInf;    // off; e.g. 8: warp triangles on reflectors bending directions more are unreliable
  float depth_discontinuity = 0.1f;  // warp corners whose s.d or s.d + s.r differ more (relative) are not connected
  float curved_contrast = 0.05f;  // ... where s·Lr varies by more than this between neighbours
  float edge_contrast = kInf;   // off; warp triangles whose corners' s·Lr differ more span a reflected edge
  std::string edge_rule = "nearest";  // there: "nearest" corner's Lr, or "recompute"
  bool recompute_splats = false;  // samples no warp triangle reached are recomputed
  float blend_error = 8.0f;     // inf = off (the thesis' method); reused samples whose expected display error (blend_risk, 0–255) exceeds this are recomputed
  float keyframe_cost = 1.0f;   // 0 = off (the thesis' policy alone); fixed steps' cost per key pixel in traced rays (TemporalOptions::keyframe_cost)
  bool match_extrapolate = false;  // best match also starts from the offsets' last change continued
  int image_frame = -1;         // frame whose images are written; −1 = the first non-key frame
  float lobe_seed_cell = 0.0f;  // > 0: glossy lobe rays seeded per world cell of this size × diagonal
  bool breakdown = false;       // with --compare: temporal error by pixel class, key-frame age, seed noise
  int reference_rays = 0;       // > 0, with --compare: also errors against a reference with this many lobe rays
};

// What a temporal run reads: the shared `reflect` flags and the temporal ones.
struct TemporalReflectRun {
  CommonOptions common;
  std::string path;       // camera path, index or name (reflect's --path)
  bool compare = false;   // also full ray tracing and direct reprojection, errors and speed-up
  int light_samples = 4;  // n of the n×n area-light stratum centres
  int glossy_rays = 16;   // lobe rays per glossy sample
  TemporalReflectFlags temporal;
};

// --threshold --stretch-limit --spread-limit (--frames --frame-step --image-frame are the cluster group's,
// copied into TemporalReflectFlags by cmd_reflect.cpp).
void add_temporal_reflect_flags(CLI::App* app, TemporalReflectFlags& flags);

// Runs the path, writes results.json (metrics, tables shaped like the thesis' Tables 22–23,
// a per-frame table) and images into --out. InputError naming the flag for bad input.
int run_temporal_reflect(const TemporalReflectRun& run);

}  // namespace proxima::cli
