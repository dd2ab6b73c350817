// `proxima bench trace`: the Embree reference's BVH build time and rays per second
// (proxima/study/trace_bench.h). `proxima bench raster`: the software rasterizer's agreement
// with Embree and its frame time (proxima/study/raster_bench.h) beside Mesa's llvmpipe
// (llvmpipe_columns.h: the optional harness proxima_llvmpipe_bench next to this binary).
// `proxima bench techniques`: every technique beside its Embree reference
// (proxima/study/technique_bench.h). `proxima bench view`: cmd_bench_view.cpp.
#include "command.h"
#include "llvmpipe_columns.h"
#include "proxima/study/raster_bench.h"
#include "proxima/study/technique_bench.h"
#include "proxima/study/trace_bench.h"
#include "scene_study.h"

namespace proxima::cli {

namespace {

struct TraceFlags {
  CommonOptions common;
  study::TraceBenchOptions options;
};

struct TechniqueFlags {
  CommonOptions common;
  study::TechniqueBenchOptions options;
};

struct RasterFlags {
  CommonOptions common;
  study::RasterBenchStudyOptions options;
};

// --scene (living-room), --camera/--path/--frame, --width/--height (1024), --threads, --out.
void add_bench_flags(CLI::App* app, CommonOptions& common, CameraChoice& camera, const char* out) {
  common.width = 1024;
  common.height = 1024;
  common.out = out;
  add_common_flags(app, common, {.scene = "living-room", .camera = &camera, .seed = false});
}

int run_techniques(TechniqueFlags& f) {
  f.options.seed = f.common.seed;
  // The techniques load their own built-in scenes; the study takes none.
  return publish_study(run_scene_study(f.common, f.options, study::run_technique_bench,
                                       {.images = false, .scene = [] { return Scene{}; }}));
}

int run_raster(RasterFlags& f) {
  set_common_options(f.common, f.options);
  SceneStudyRun run = run_scene_study(f.common, f.options, study::run_raster_bench, {.images = false});
  add_llvmpipe_columns(run.results, llvmpipe_run(f.common.scene, f.options, run.results));
  return publish_study(std::move(run));
}

}  // namespace

Command register_bench(CLI::App& root) {
  static TraceFlags t;
  static RasterFlags r;
  static TechniqueFlags k;
  auto* app = root.add_subcommand("bench", "benchmarks (medians of repetitions, written to results.json)");
  app->require_subcommand(1);
  auto* trace = app->add_subcommand("trace", "Embree reference: BVH build, primary and reflection rays per second");
  add_bench_flags(trace, t.common, t.options.camera, "out/bench-trace");
  trace->add_option("--reps", t.options.reps, "repetitions per measurement")->capture_default_str();

  auto* raster = app->add_subcommand(
      "raster", "software rasterizer: id agreement with Embree on every built-in camera; ms/frame vs llvmpipe");
  add_bench_flags(raster, r.common, r.options.camera, "out/bench-raster");
  raster->add_option("--reps", r.options.reps, "repetitions per measurement")->capture_default_str();
  raster->add_flag("--skip-agreement", r.options.skip_agreement, "time only; skip the Embree agreement pass");
  auto* tech = app->add_subcommand(
      "techniques", "every technique beside its Embree reference at the demo's settings: ratios, error vs ms");
  k.common.out = "out/bench-techniques";
  add_common_flags(tech, k.common, {.scene = nullptr, .size = false});
  tech->add_option("--techniques", k.options.techniques, "comma-separated: envmap,cluster,temporal,sampling,"
                                                         "shadows,visibility, or all")->capture_default_str();
  tech->add_option("--reps", k.options.reps, "interleaved repetitions per point (medians)")->capture_default_str();
  tech->add_flag("!--no-sweep", k.options.sweep, "only the demo's settings, not the other settings of each knob");
  const Command view = register_bench_view(*app);
  return {app, [trace, raster, tech, view] {
            if (trace->parsed()) {
              set_common_options(t.common, t.options);
              return publish_study(run_scene_study(t.common, t.options, study::run_trace_bench, {.images = false}));
            }
            if (raster->parsed()) return run_raster(r);
            if (tech->parsed()) return run_techniques(k);
            if (view.app->parsed()) return view.run();
            return 2;
          }};
}

}  // namespace proxima::cli
