// Every technique beside its Embree reference, timed side by side: env maps (each method,
// the box probe among them), cluster reflections (with screen-space reflections and their
// box-probe fallback on the same frames and rays at the demo's setting), temporal reuse,
// depth-image sampling, soft shadows and visibility maps, each at the demo's settings (its
// section of `proxima demo`; env maps, cluster, temporal and shadows run the demo's own
// planned study runs, study::plan_demo) and at a few other settings of its main knob (cube
// size, depth-image resolution, key-frame threshold, shadow-map resolution, image size), so
// a user can read error against milliseconds and choose.
// What `proxima bench techniques` runs; the demo's "bench" section shows the same tables.
//
// Timing: a repetition runs every point once, technique by technique; each run measures the
// approximation and its reference in the same call (the studies' own side-by-side timing,
// or an Embree item buffer right after the run), so both sides see the same machine load.
// The figures are medians over the repetitions, at the caller's thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/scene/scene.h"
#include "proxima/study/study.h"

namespace proxima::study {

// The technique names, in report order: envmap, cluster, temporal, sampling, shadows, visibility.
const std::vector<std::string>& technique_bench_names();

// The options of `proxima bench techniques`, one field per flag, with the flag's default.
struct TechniqueBenchOptions {
  std::string techniques = "all";  // --techniques: comma-separated technique_bench_names(), or "all"
  int reps = 5;                    // --reps: interleaved repetitions, 1..100 (medians reported)
  bool sweep = true;               // --no-sweep clears it: only the demo's settings, no other settings
  uint64_t seed = 1;               // --seed: the studies' sample streams
};

// Throws InputError naming the flag (--techniques, --reps).
void validate(const TechniqueBenchOptions& options);

// One measured setting of one technique (medians over the repetitions).
struct TechniquePoint {
  std::string technique;  // a technique_bench_names() entry
  std::string method;     // the variant: "rectified", "living-room walk", "nrr", …
  std::string knob;       // the setting varied: "cube size", "resolution scale", …
  double knob_value = 0;  // its value
  bool demo = false;      // the demo's setting
  double ms = 0;          // the approximation, ms per frame (or per view / per image set)
  double reference_ms = 0;          // Embree on the same work, ms, BVH built beforehand
  double reference_build_ms = 0;    // Embree's BVH build alone, ms (0 = not timed)
  double approximation_build_ms = 0;  // the approximation's per-scene preparation not in `ms` (0 = none)
  double error = 0;                 // the approximation's error against Embree (unit in error_unit)
  std::string error_unit;           // "MAE 0–255", "% samples missing", …
};

// The points one run of `technique`'s study gives at one setting, from its metrics `m`
// (looked up by the study's metric names; for sampling and visibility also "embree_ms" and
// "embree_build_ms", Embree's item buffers of the same views). `where` names the scene.
// A cluster run with ssr (finite "ssr_ms_avg") gives a second point, method "ssr <where>",
// knob "max steps": ms ssr_ms_avg, error the mean of ssr_mae_r/g/b, preparation the
// fallback's cube-map build (envmap_build_ms_avg), Embree as the cluster point's.
std::vector<TechniquePoint> technique_points(const std::string& technique, const std::string& where,
                                             const std::string& knob, double knob_value, bool demo,
                                             const std::function<double(const std::string&)>& m);

// The points of the chosen techniques: the demo's settings (demo = true) and, with
// options.sweep, the other settings. Runs each point options.reps times, interleaved.
std::vector<TechniquePoint> measure_techniques(const TechniqueBenchOptions& options, bool demo_settings,
                                               Progress* progress = nullptr);

// The report of a set of points. Table "Techniques vs Embree at the demo's settings" (one
// row per demo point: ms, Embree ms, ratio = Embree ms ÷ approximation ms, > 1 = faster than
// Embree, the same with the preparation counted on both sides, error), table "Error vs ms:
// <technique>" per technique (one row per point; the Embree point with error 0) with its
// line plot in section "bench". Metrics per demo point `<technique>_<method>_ratio`, `_ms`,
// `_embree_ms`, `_error` (method with ' ' and '/' as '_').
Results technique_bench_results(const std::vector<TechniquePoint>& points);

// Runs the study: measure_techniques(options, true) and its report. `scene` is not used:
// every technique runs on the built-in scenes of its demo section. No images.
Results run_technique_bench(const Scene& scene, const TechniqueBenchOptions& options, const StudyOutput& out,
                            Progress* progress = nullptr);

}  // namespace proxima::study
