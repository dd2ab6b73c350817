// `proxima reflect --method cluster` (issue 7): reflections from screen-space clustered
// depth images on one camera or along a camera path, with --compare against Embree tracing
// the same rays and against environment mapping with position rectification (issue 6).
// cmd_reflect.cpp owns the shared flags and dispatches here.
#pragma once

#include <string>

#include "command.h"
#include "proxima/reflect/cluster_reflection.h"

namespace proxima::cli {

struct ClusterReflectFlags {
  // Shared with the env-map methods; cmd_reflect.cpp copies them in before the run.
  CommonOptions common;
  CameraChoice camera;       // --camera, or --path (with --frame: that frame only)
  bool frame_given = false;  // --frame was given
  bool compare = false;      // Embree on the same rays + env mapping: errors, occlusion errors, timing
  int reps = 1;              // timing repetitions per frame (medians)
  // The env-map comparison (rectified lookups on one distance cube map per frame).
  int cube_size = 512;
  float d_e = 0.01f;
  float distance = 0.0f;  // D; 0 = the scene's bounding-box diagonal
  bool edge_fallback = false;
  // Cluster-only flags (add_cluster_reflect_flags).
  int frames = 0;          // frames the path is divided into; 0 = the path's own count
  int frame_step = 1;      // run every frame_step-th frame
  int image_frame = -1;    // frame whose images are written; −1 = the first one rendered
  bool full_reference = false;  // also render_reference (shadows, jittered area light, 1 bounce): errors
  ReflectionOptions reflection;
  ClusterReflectionOptions cluster;
};

// Adds the cluster-only flags (--frames --frame-step --ss --theta-bins --phi-bins
// --resolution-scale --image-frame --full-reference) to `app`.
void add_cluster_reflect_flags(CLI::App* app, ClusterReflectFlags& flags);

// Runs the frames, writes images of one frame and results.json into --out, prints the
// tables. Throws InputError naming the flag for bad input (before anything is written).
int run_cluster_reflect(const ClusterReflectFlags& flags);

}  // namespace proxima::cli
