// `proxima reflect --method temporal`: the flags of study/temporal_reflect.h. cmd_reflect.cpp
// owns the flags shared with the other methods and dispatches here.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "command.h"
#include "proxima/study/temporal_reflect.h"

namespace proxima::cli {

// The study's options; add_temporal_reflect_flags binds the temporal-only ones, cmd_reflect.cpp
// copies --frames --frame-step --image-frame (the cluster group's) in.
using TemporalReflectFlags = study::TemporalReflectOptions;

// What a temporal run reads: the shared `reflect` flags and the temporal ones.
struct TemporalReflectRun {
  CommonOptions common;
  std::string path;       // camera path, index or name (reflect's --path)
  bool compare = false;   // also full ray tracing and direct reprojection, errors and speed-up
  int light_samples = 4;  // n of the n×n area-light stratum centres
  int glossy_rays = 16;   // lobe rays per glossy sample
  TemporalReflectFlags temporal;
};

// --threshold --stretch-limit --spread-limit --curved-contrast --edge-contrast --edge-rule
// --recompute-splats --blend-error --keyframe-cost --match-extrapolate --depth-discontinuity
// --lobe-seed-cell --breakdown --reference-rays.
void add_temporal_reflect_flags(CLI::App* app, TemporalReflectFlags& flags);

// Runs the study, writes results.json (with the per-frame table, which is not printed) and
// images into --out. InputError naming the flag for bad input (before anything is written).
int run_temporal_reflect(const TemporalReflectRun& run);

}  // namespace proxima::cli
