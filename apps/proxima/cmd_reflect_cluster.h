// The cluster depth-image reflection run (issue 7), callable from `proxima reflect-cluster`
// now and from `proxima reflect --method cluster` once both commands merge.
#pragma once

#include <string>

#include "command.h"
#include "proxima/reflect/cluster_reflection.h"

namespace proxima::cli {

struct ClusterReflectFlags {
  CommonOptions common;
  std::string path = "0";   // camera path, index or name
  int frames = 0;           // frames the path is divided into; 0 = the path's own count
  int frame_step = 1;       // run every frame_step-th frame
  int reps = 1;             // timing repetitions per frame (medians)
  int image_frame = -1;     // frame whose images are written; −1 = the first one rendered
  bool compare = false;     // also trace the same rays with Embree: errors, occlusion errors, timing
  bool full_reference = false;  // also render_reference (shadows, jittered area light, --bounces 1): errors
  ReflectionOptions reflection;
  ClusterReflectionOptions cluster;
};

// Adds the flags (--scene --path --frames --frame-step --width --height --ss --gloss-rays
// --light-samples --theta-bins --phi-bins --resolution-scale --reps --image-frame --compare --full-reference --threads
// --seed --out) to `app`, `out_required` for --out.
void add_cluster_reflect_flags(CLI::App* app, ClusterReflectFlags& flags, bool out_required);

// Runs the frames, writes color/reference/error images of the first frame and results.json
// into --out, prints the tables. Throws InputError naming the flag for bad input.
int run_cluster_reflect(const ClusterReflectFlags& flags);

}  // namespace proxima::cli
