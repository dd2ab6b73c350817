// Google Benchmark micro-benchmarks of the fixed per-frame steps of temporal reflection
// reuse: best match (Algorithm 9), grid-mesh offset warp and depth reprojection,
// on living-room / walk as `proxima reflect --method temporal` renders it (500 frames, 8
// lobe rays): key frame 100, warm-started through frames 101–104, timed on frame 105 (10% reflective pixels).
// Arg: image side; `rules`: 1 = --spread-limit 8 --curved-contrast 0.05 --edge-contrast
// 0.05 --edge-rule recompute --recompute-splats; reprojection's `blend`: the mesh's
// blend_error (0 = off; 8 = the CLI's default --blend-error, which times the risk test). 1 thread. The figures in docs/journal/temporal.md
// come from `proxima reflect --compare`; these are for profiling.
// BM_TemporalWalk is the whole method through the library: the walk at side², every frame
// temporal reuse beside full reflection ray tracing (as `proxima reflect --method temporal
// --path walk --glossy-rays R --threshold 0.3 --compare --threads N` with the CLI's
// defaults; `rays` R = 16 is the CLI's default, 8 the lobe the journal's figures use), so its
// buffers get what every library user gets (core/large_buffer.h).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <utility>

#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/reflect/temporal_reuse.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"

namespace {

using namespace proxima;

constexpr int kFrames = 500, kKeyFrame = 100, kWarmFrames = 4;

struct Walk {
  Walk(int side, bool rules) {
    if (rules) {
      options.warp.spread_limit = 8.0f;
      options.warp.curved_contrast = 0.05f;
      options.warp.edge_contrast = 0.05f;
      options.warp.edge_rule = ReflectedEdgeRule::kRecompute;
      options.warp.recompute_splats = true;
    }
    options.keyframe_threshold = 2.0f;  // keep the one key frame
    ThreadLimit limit(2);
    const CameraPath& path = scene.camera_paths.front();
    const float t0 = path.keys.front().time, t1 = path.keys.back().time;
    const float far = scene_far_plane(scene);
    ReflectionOptions ro;
    ro.supersample = 1;
    ro.glossy_rays = 8;
    for (int f = kKeyFrame; f <= kKeyFrame + kWarmFrames + 1; ++f) {
      const float t = t0 + float(f) * (t1 - t0) / float(kFrames - 1);
      frame = prepare_reflection_frame(scene, camera_at_time(path, t, side, side, 0.01f, far), ro);
      if (f <= kKeyFrame + kWarmFrames) temporal_reflections(scene, rays, frame, state, options);
    }
    offsets = best_match_search(state.key, frame.camera.position, &state.previous, options.match);
    mid = warp_reflections(state.key, offsets, options.warp);
  }
  Scene scene = make_builtin_scene("living-room");
  RayScene rays{scene};
  TemporalOptions options;
  TemporalState state;
  ReflectionFrame frame;  // the timed frame
  OffsetBuffer offsets;
  IntermediateReflection mid;
};

const Walk& walk(int side, bool rules) {
  static std::map<std::pair<int, bool>, std::unique_ptr<Walk>> cache;
  auto& w = cache[{side, rules}];
  if (!w) w = std::make_unique<Walk>(side, rules);
  return *w;
}

void BM_TemporalBestMatch(benchmark::State& state) {
  const Walk& w = walk(int(state.range(0)), state.range(1) != 0);
  ThreadLimit limit(1);
  BestMatchStats stats;
  for (auto _ : state)
    benchmark::DoNotOptimize(
        best_match_search(w.state.key, w.frame.camera.position, &w.state.previous, w.options.match, &stats));
  state.counters["steps_per_px"] = double(stats.steps) / double(std::max<uint64_t>(stats.searched, 1));
  state.counters["reflective"] = double(stats.searched);
}

// As temporal_reflections runs it: into a buffer reused from frame to frame (no fresh
// 9-byte-per-pixel allocation per call).
void BM_TemporalBestMatchInto(benchmark::State& state) {
  const Walk& w = walk(int(state.range(0)), state.range(1) != 0);
  ThreadLimit limit(1);
  BestMatchStats stats;
  OffsetBuffer out;
  for (auto _ : state) {
    best_match_search_into(w.state.key, w.frame.camera.position, &w.state.previous, w.options.match, out, &stats);
    benchmark::DoNotOptimize(out.offset.data());
  }
  state.counters["steps_per_px"] = double(stats.steps) / double(std::max<uint64_t>(stats.searched, 1));
}

void BM_TemporalWarp(benchmark::State& state) {
  const Walk& w = walk(int(state.range(0)), state.range(1) != 0);
  ThreadLimit limit(1);
  IntermediateReflection mid;  // reused frame to frame, as temporal_reflections does
  for (auto _ : state) {
    warp_reflections_into(w.state.key, w.offsets, w.options.warp, mid);
    benchmark::DoNotOptimize(mid.triangles);
  }
  state.counters["triangles"] = double(mid.triangles);
  state.counters["discontinuous"] = double(mid.discontinuous);
}

void BM_TemporalReproject(benchmark::State& state) {
  const Walk& w = walk(int(state.range(0)), state.range(1) != 0);
  ThreadLimit limit(1);
  const float blend_error = state.range(2) > 0 ? float(state.range(2)) : kInf;
  const WarpedMesh mesh{&w.state.key, &w.offsets, &w.mid, w.options.warp.edge_contrast, w.options.warp.edge_rule,
                        w.options.warp.recompute_splats, blend_error};
  uint64_t recompute = 0;
  ReflectionReprojection r;  // reused frame to frame, as temporal_reflections does
  for (auto _ : state) {
    reproject_reflections_into(w.frame, w.state.key, w.mid.radiance, &w.mid.state, w.options.reproject, &mesh, r);
    recompute = r.recompute();
    benchmark::DoNotOptimize(recompute);
  }
  state.counters["recompute"] = double(recompute);
}

void BM_TemporalTrace(benchmark::State& state) {  // full reflection ray tracing of the frame, for scale
  const Walk& w = walk(int(state.range(0)), state.range(1) != 0);
  ThreadLimit limit(1);
  for (auto _ : state) benchmark::DoNotOptimize(trace_reflections(w.scene, w.rays, w.frame));
}

// A key frame's work beyond the trace: the reflection depth image from the traced frame.
void BM_TemporalDepthImage(benchmark::State& state) {
  const Walk& w = walk(int(state.range(0)), state.range(1) != 0);
  ThreadLimit limit(1);
  const TracedReflections traced = trace_reflections(w.scene, w.rays, w.frame);
  ReflectionDepthImage key;  // rebuilt in place, as temporal_reflections does
  for (auto _ : state) {
    make_reflection_depth_image_into(w.frame, traced, 100.0f * w.frame.scene_diagonal, key);
    benchmark::DoNotOptimize(key.reflected.data());
  }
  state.counters["reflective"] = double(key.pixels.size());
}

// The shared first step of every frame: G-buffer, base shading and ray set-up
// (prepare_reflection_frame), and the final blend, on the timed frame.
void BM_ReflectionFramePrepare(benchmark::State& state) {
  const Walk& w = walk(int(state.range(0)), false);
  ThreadLimit limit(int(state.range(1)));
  ReflectionOptions ro;
  ro.supersample = 1;
  ro.glossy_rays = 8;
  for (auto _ : state) benchmark::DoNotOptimize(prepare_reflection_frame(w.scene, w.frame.camera, ro).base.data().data());
}

void BM_ReflectionCompose(benchmark::State& state) {
  const Walk& w = walk(int(state.range(0)), false);
  ThreadLimit limit(int(state.range(1)));
  const std::vector<vec3> reflected(w.frame.sample_count(), vec3(0.25f));
  for (auto _ : state) benchmark::DoNotOptimize(compose_reflections(w.frame, reflected).data().data());
}

// The walk's `frames` frames, each: the G-buffer, temporal reuse (timed), full reflection
// tracing of the same frame (timed), the blend (timed). Counters: mean ms per frame of each
// and their ratio, for the reflection work alone and for the whole frame (G-buffer, base
// shading and ray set-up, reflections, blend: what a user waits for). `scene`: 0 =
// living-room, 1 = bathroom (each along its walk); `blend`: --blend-error (8, the CLI's
// default). Untimed: the MAE against the full trace, as `proxima reflect --compare` gives it.
void BM_TemporalWalk(benchmark::State& state) {
  const int side = int(state.range(0)), frames = int(state.range(1)), threads = int(state.range(2));
  const Scene scene = make_builtin_scene(state.range(3) == 0 ? "living-room" : "bathroom");
  const RayScene rays(scene);
  const CameraPath& path = scene.camera_paths[size_t(find_camera_path(scene, "walk"))];
  const float t0 = path.keys.front().time, t1 = path.keys.back().time;
  const float far = scene_far_plane(scene);
  ReflectionOptions ro;
  ro.supersample = 1;
  ro.glossy_rays = int(state.range(5));
  TemporalOptions to;  // the CLI's defaults where they differ from the library's
  to.keyframe_threshold = 0.3f;
  to.keyframe_cost = 1.0f;
  to.warp.blend_error = float(state.range(4));
  ThreadLimit limit(threads);
  // Wall and process CPU time: on a shared machine the CPU times are the steadier figures.
  double temporal_ms = 0.0, reference_ms = 0.0, temporal_cpu = 0.0, reference_cpu = 0.0;
  double shared_ms = 0.0, shared_cpu = 0.0;  // G-buffer pass and one blend per frame, both sides
  double key_ms = 0.0, match_ms = 0.0, warp_ms = 0.0, reproject_ms = 0.0, recompute_ms = 0.0;  // wall, per step
  double key_cpu = 0.0, key_reference_cpu = 0.0;  // CPU time of the key frames, temporal and full trace
  double recompute_pct = 0.0;      // Σ recomputed % of the reuse frames
  double match_steps = 0.0, match_pixels = 0.0;  // Σ best-match descent steps and searched pixels
  double mae = 0.0;                // Σ MAE against the full trace (untimed), frames with reflective pixels
  int keyframes = 0, mae_frames = 0;
  for (auto _ : state) {
    TemporalState temporal;
    // Buffers reused frame to frame, as the CLI does: the G-buffer pass's, the full trace's
    // (as the key frames' trace) and the blend's.
    ReflectionFrame frame;
    TracedReflections traced;
    ImageF composite;
    std::vector<vec3> reflected;
    std::vector<uint8_t> flags;
    temporal_ms = reference_ms = temporal_cpu = reference_cpu = shared_ms = shared_cpu = 0.0;
    key_ms = match_ms = warp_ms = reproject_ms = recompute_ms = 0.0;
    keyframes = mae_frames = 0;
    key_cpu = key_reference_cpu = recompute_pct = match_steps = match_pixels = mae = 0.0;
    for (int f = 0; f < frames; ++f) {
      const float t = frames > 1 ? t0 + float(f) * (t1 - t0) / float(frames - 1) : t0;
      Stopwatch shared;
      double cpu = process_cpu_ms();
      prepare_reflection_frame_into(scene, camera_at_time(path, t, side, side, 0.01f, far), ro, frame);
      shared_cpu += process_cpu_ms() - cpu;
      shared_ms += shared.elapsed_ms();
      TemporalFrameStats st;
      cpu = process_cpu_ms();
      temporal_reflections_into(scene, rays, frame, temporal, to, reflected, &st, &flags);
      const double step_cpu = process_cpu_ms() - cpu;
      temporal_cpu += step_cpu;
      if (st.key) {
        key_cpu += step_cpu;
      } else {
        recompute_pct += 100.0 * st.recompute_fraction();
        match_steps += double(st.match_steps), match_pixels += double(st.reflective);
      }
      temporal_ms += st.reflection_ms();
      keyframes += st.key ? 1 : 0;
      key_ms += st.key_ms, match_ms += st.match_ms, warp_ms += st.warp_ms;
      reproject_ms += st.reproject_ms, recompute_ms += st.recompute_ms;
      Stopwatch watch;
      cpu = process_cpu_ms();
      trace_reflections_into(scene, rays, frame, traced);
      const double trace_cpu = process_cpu_ms() - cpu;
      reference_cpu += trace_cpu;
      reference_ms += watch.elapsed_ms();
      if (st.key) key_reference_cpu += trace_cpu;
      benchmark::DoNotOptimize(traced.radiance.data());
      shared.restart();
      cpu = process_cpu_ms();
      compose_reflections_into(frame, reflected, composite);
      shared_cpu += process_cpu_ms() - cpu;
      shared_ms += shared.elapsed_ms();
      if (frame.sample_count() > 0) {  // the CLI's temporal_mae_avg (`proxima reflect --compare`)
        const ImageU8 mask = reflective_pixel_mask(frame);
        mae += compare_images(composite, compose_reflections(frame, traced.radiance), &mask).mae_avg;
        ++mae_frames;
      }
    }
  }
  state.counters["temporal_ms"] = temporal_ms / frames;
  state.counters["reference_ms"] = reference_ms / frames;
  state.counters["speedup"] = temporal_ms > 0.0 ? reference_ms / temporal_ms : 0.0;
  state.counters["temporal_cpu_ms"] = temporal_cpu / frames;
  state.counters["reference_cpu_ms"] = reference_cpu / frames;
  state.counters["speedup_cpu"] = temporal_cpu > 0.0 ? reference_cpu / temporal_cpu : 0.0;
  state.counters["keyframes"] = keyframes;
  state.counters["mae"] = mae_frames > 0 ? mae / mae_frames : 0.0;
  state.counters["recompute_pct"] = keyframes < frames ? recompute_pct / double(frames - keyframes) : 0.0;
  state.counters["match_steps_per_px"] = match_pixels > 0.0 ? match_steps / match_pixels : 0.0;
  state.counters["key_cpu_ms"] = key_cpu / frames;  // per frame of the walk, key frames amortized
  state.counters["key_reference_cpu_ms"] = key_reference_cpu / frames;  // the full trace on those frames
  state.counters["key_ms"] = key_ms / frames;  // per frame of the walk, key frames amortized
  state.counters["match_ms"] = match_ms / frames;
  state.counters["warp_ms"] = warp_ms / frames;
  state.counters["reproject_ms"] = reproject_ms / frames;
  state.counters["recompute_ms"] = recompute_ms / frames;
  state.counters["shared_ms"] = shared_ms / frames;
  state.counters["shared_cpu_ms"] = shared_cpu / frames;
  state.counters["frame_speedup_cpu"] =
      shared_cpu + temporal_cpu > 0.0 ? (shared_cpu + reference_cpu) / (shared_cpu + temporal_cpu) : 0.0;
}

#define TEMPORAL_ARGS ArgsProduct({{256, 512, 1024}, {0, 1}})->ArgNames({"side", "rules"})->Unit(benchmark::kMillisecond)
BENCHMARK(BM_TemporalBestMatch)->TEMPORAL_ARGS;
BENCHMARK(BM_TemporalBestMatchInto)->TEMPORAL_ARGS;
BENCHMARK(BM_TemporalWarp)->TEMPORAL_ARGS;
BENCHMARK(BM_TemporalReproject)
    ->ArgsProduct({{256, 512, 1024}, {0, 1}, {0, 8}})
    ->ArgNames({"side", "rules", "blend"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TemporalDepthImage)->ArgsProduct({{256, 512, 1024}, {0}})->ArgNames({"side", "rules"})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TemporalTrace)->ArgsProduct({{256, 512, 1024}, {0}})->ArgNames({"side", "rules"})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReflectionFramePrepare)->ArgsProduct({{1024}, {1, 2}})->ArgNames({"side", "threads"})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReflectionCompose)->ArgsProduct({{1024}, {1, 2}})->ArgNames({"side", "threads"})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TemporalWalk)
    ->ArgsProduct({{1024}, {100, 500}, {1, 2}, {0, 1}, {8, 12, 16}, {8, 16}})
    ->ArgNames({"side", "frames", "threads", "scene", "blend", "rays"})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
