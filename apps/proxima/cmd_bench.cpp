// `proxima bench trace`: the Embree reference's BVH build time and rays per second
// (proxima/study/trace_bench.h). `proxima bench raster`: the software rasterizer's agreement
// with Embree and its frame time beside Mesa's llvmpipe (proxima/study/raster_bench.h; the
// optional harness proxima_llvmpipe_bench next to this binary). `proxima bench view`:
// cmd_bench_view.cpp.
#include <filesystem>

#include "command.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/load.h"
#include "proxima/study/raster_bench.h"
#include "proxima/study/trace_bench.h"

namespace proxima::cli {

namespace {

struct TraceFlags {
  CommonOptions common;
  study::TraceBenchOptions options;
};

struct RasterFlags {
  CommonOptions common;
  study::RasterBenchStudyOptions options;
};

// --scene (living-room), --camera/--path/--frame, --width/--height (1024), --threads, --out.
void add_bench_flags(CLI::App* app, CommonOptions& common, CameraChoice& camera, const char* out) {
  add_scene_flag(app, common, "living-room");
  add_camera_flags(app, camera);
  common.width = 1024;
  common.height = 1024;
  add_size_flags(app, common);
  add_threads_flag(app, common);
  add_out_flag(app, common, false);
  common.out = out;
}

int run_trace(TraceFlags& f) {
  study::TraceBenchOptions& o = f.options;
  o.width = f.common.width;
  o.height = f.common.height;
  o.threads = f.common.threads;
  study::validate(o);
  ThreadLimit limit(f.common.threads);
  const Scene scene = load_scene(f.common.scene);
  pick_camera(scene, o.camera, o.width, o.height);  // a bad camera choice fails before --out exists
  const auto out = prepare_out_dir(f.common.out);
  return publish_study(out, study::run_trace_bench(scene, o, {}));
}

int run_raster(RasterFlags& f) {
  study::RasterBenchStudyOptions& o = f.options;
  o.width = f.common.width;
  o.height = f.common.height;
  o.threads = f.common.threads;
  o.llvmpipe_scene = f.common.scene;
  o.llvmpipe_harness = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "proxima_llvmpipe_bench";
  study::validate(o);
  ThreadLimit limit(f.common.threads);
  const Scene scene = load_scene(f.common.scene);
  pick_camera(scene, o.camera, o.width, o.height);
  const auto out = prepare_out_dir(f.common.out);
  return publish_study(out, study::run_raster_bench(scene, o, {}));
}

}  // namespace

Command register_bench(CLI::App& root) {
  static TraceFlags t;
  static RasterFlags r;
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
  const Command view = register_bench_view(*app);
  return {app, [trace, raster, view] {
            if (trace->parsed()) return run_trace(t);
            if (raster->parsed()) return run_raster(r);
            if (view.app->parsed()) return view.run();
            return 2;
          }};
}

}  // namespace proxima::cli
