// `proxima reflect --method cluster`: the flags of study/cluster_reflect.h. cmd_reflect.cpp
// owns the flags shared with the env-map methods, copies them in and dispatches here.
#pragma once

#include "command.h"
#include "proxima/study/cluster_reflect.h"

namespace proxima::cli {

// The study's options, bound to flags, plus the common ones (cmd_reflect.cpp copies
// --scene --width --height --threads --seed --out into `common` before the run).
struct ClusterReflectFlags : study::ClusterReflectOptions {
  CommonOptions common;
};

// Adds the cluster-only flags (--frames --frame-step --ss --theta-bins --phi-bins
// --min-bin-scale --resolution-scale --second-layer --own-exact --march-block --image-frame
// --full-reference) to `app`.
void add_cluster_reflect_flags(CLI::App* app, ClusterReflectFlags& flags);

// Runs the study, writes its images and results.json into --out, prints the tables. Throws
// InputError naming the flag for bad input (before anything is written).
int run_cluster_reflect(const ClusterReflectFlags& flags);

}  // namespace proxima::cli
