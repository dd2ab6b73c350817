// `proxima reflect --method temporal`: temporal reuse of reflections (issue 8, thesis ch. 5)
// along a camera path. With --compare every frame is also fully ray traced (the reference,
// timed side by side) and rendered by direct depth reprojection of the same key frame.
#include "cmd_reflect_temporal.h"
#include "frame_series.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/reflect/temporal_reuse.h"
#include "proxima/scene/load.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::cli {

namespace {


// Error heat maps saturate here (0–255 units).
constexpr float kHeatmapMax = 20.0f;

int find_path(const Scene& scene, const std::string& key) {
  if (!key.empty() && key.find_first_not_of("0123456789") == std::string::npos) {
    const size_t i = std::stoul(key);
    return i < scene.camera_paths.size() ? int(i) : -1;
  }
  for (size_t i = 0; i < scene.camera_paths.size(); ++i)
    if (scene.camera_paths[i].name == key) return int(i);
  return -1;
}

void validate(const TemporalReflectRun& r) {
  const auto& c = r.common;
  const auto& t = r.temporal;
  if (c.width < 1 || c.width > 4096) fail_input("--width: must be in 1..4096");
  if (c.height < 1 || c.height > 4096) fail_input("--height: must be in 1..4096");
  if (c.threads < 0) fail_input("--threads: must be ≥ 0");
  if (r.path.empty()) fail_input("--path: --method temporal needs a camera path (index or name)");
  if (r.light_samples < 1 || r.light_samples > 64) fail_input("--light-samples: must be in 1..64");
  if (r.glossy_rays < 1 || r.glossy_rays > 1024) fail_input("--glossy-rays: must be in 1..1024 for --method temporal");
  if (t.frames < 0 || t.frames > 100000) fail_input("--frames: must be in 0..100000");
  if (t.frame_step < 1 || t.frame_step > 100000) fail_input("--frame-step: must be in 1..100000");
  if (!(t.threshold >= 0.0f && t.threshold <= 1.0f)) fail_input("--threshold: must be in [0, 1]");
  if (!(t.stretch_limit >= 1.0f) || !std::isfinite(t.stretch_limit)) fail_input("--stretch-limit: must be ≥ 1");
  if (!(t.spread_limit >= 1.0f)) fail_input("--spread-limit: must be ≥ 1 (inf = off)");
  if (!(t.curved_contrast >= 0.0f)) fail_input("--curved-contrast: must be ≥ 0");
  if (t.image_frame < -1) fail_input("--image-frame: must be ≥ -1");
}

// The frame dimmed, recomputed samples red (disoccluded) and orange (unreliable warp).
ImageF recompute_image(const ReflectionFrame& frame, const std::vector<uint8_t>& flags, const ImageF& color) {
  ImageF out = color;
  for (float& v : out.data()) v *= 0.3f;
  const int w = frame.camera.width;
  for (size_t i = 0; i < flags.size(); ++i) {
    if (flags[i] == kReuseOk) continue;
    const vec3 c = (flags[i] & kReuseDisoccluded) ? vec3(1, 0, 0) : vec3(1, 0.5f, 0);
    const int x = int(frame.pixel[i] % uint32_t(w)), y = int(frame.pixel[i] / uint32_t(w));
    for (int ch = 0; ch < 3; ++ch) out.at(x, y, ch) = c[ch];
  }
  return out;
}

}  // namespace

void add_temporal_reflect_flags(CLI::App* app, TemporalReflectFlags& f) {
  app->add_option("--threshold", f.threshold,
                  "temporal: next frame is a key frame when more than this fraction of reflective pixels was recomputed")
      ->capture_default_str();
  app->add_option("--stretch-limit", f.stretch_limit,
                  "temporal: warped grid triangles stretched more than this (area ratio) are unreliable")
      ->capture_default_str();
  app->add_option("--spread-limit", f.spread_limit,
                  "temporal: warped grid triangles on a reflector that spreads neighbouring pixels' reflection "
                  "directions more than this many times their view angle (curved mirrors) are unreliable; inf = off")
      ->capture_default_str();
  app->add_option("--curved-contrast", f.curved_contrast,
                  "temporal: ... only where s*Lr differs between neighbouring key pixels by more than this (linear)")
      ->capture_default_str();
}

int run_temporal_reflect(const TemporalReflectRun& run) {
  validate(run);
  const TemporalReflectFlags& tf = run.temporal;
  ThreadLimit limit(run.common.threads);
  const Scene rest = load_scene(run.common.scene);
  const int path_index = find_path(rest, run.path);
  if (path_index < 0)
    fail_input("--path: scene '" + rest.name + "' has no camera path '" + run.path + "' (" +
               std::to_string(rest.camera_paths.size()) + " paths)");
  if (reflective_objects(rest).empty()) fail_input("--scene: '" + run.common.scene + "' has no reflective object");
  const CameraPath& path = rest.camera_paths[size_t(path_index)];
  const int frames = tf.frames > 0 ? tf.frames : path.frames;
  const auto out = prepare_out_dir(run.common.out);
  const float t_first = path.keys.front().time, t_last = path.keys.back().time;
  const float far = std::max(10.0f, 4.0f * scene_bounds(rest).diagonal());
  const bool animated = has_animation(rest);

  ReflectionOptions ro;
  ro.supersample = 1;
  ro.glossy_rays = run.glossy_rays;
  ro.area_light_samples = run.light_samples;
  ro.seed = run.common.seed;
  TemporalOptions to;
  to.keyframe_threshold = tf.threshold;
  to.warp.stretch_limit = tf.stretch_limit;
  to.warp.spread_limit = tf.spread_limit;
  to.warp.curved_contrast = tf.curved_contrast;

  Scene scene = animated ? pose_scene(rest, t_first) : rest;
  RayScene rays(scene);
  TemporalState state;
  Series mirror_temporal_mae, mirror_direct_mae;
  Series reflective_pct, recompute_pct, traced_pct, temporal_mae, direct_mae, direct_recompute_pct, temporal_ms,
      reference_ms, frame_temporal_ms, frame_reference_ms, diffuse_ms, key_ms, match_ms, warp_ms, reproject_ms,
      recompute_ms, compose_ms, intervals, curved_pct;
  Table per_frame{"Per frame", {"frame", "key", "reflective_pct", "recompute_pct", "disoccluded_pct", "unreliable_pct",
                                "temporal_mae", "direct_mae", "diffuse_ms", "key_ms", "match_ms", "warp_ms",
                                "reproject_ms", "recompute_ms", "compose_ms", "reference_trace_ms"}, {}};
  Results results;
  results.command = command_line();
  results.threads = active_threads();
  bool wrote_images = false;
  int keyframes = 0, since_key = 0;
  for (int frame_index = 0; frame_index < frames; frame_index += tf.frame_step) {
    const float t = frames > 1 ? t_first + float(frame_index) * (t_last - t_first) / float(frames - 1) : t_first;
    if (animated) {
      // Reuse assumes a static scene (thesis §5.5.4); moving parts are posed but reused as is.
      scene = pose_scene(rest, t);
      rays.update(scene);
    }
    const Camera camera = camera_at_time(path, t, run.common.width, run.common.height, 0.01f, far);

    // Shared by both methods: the G-buffer and the diffuse (non-reflected) shading.
    Stopwatch watch;
    const ReflectionFrame frame = prepare_reflection_frame(scene, camera, ro);
    const double diffuse = watch.elapsed_ms();
    TemporalFrameStats st;
    std::vector<uint8_t> flags;
    const std::vector<vec3> reflected = temporal_reflections(scene, rays, frame, state, to, &st, &flags);
    watch.restart();
    const ImageF color = compose_reflections(frame, reflected);
    const double compose = watch.elapsed_ms();

    const double n = std::max<double>(1.0, double(st.reflective));
    reflective_pct.add(100.0 * double(st.reflective) / double(camera.width * camera.height));
    if (st.key) {
      if (keyframes > 0) intervals.add(double(since_key));
      ++keyframes;
      since_key = 0;
      key_ms.add(st.key_ms);
      traced_pct.add(st.reflective ? 100.0 : 0.0);
    } else {
      recompute_pct.add(100.0 * st.recompute_fraction());
      curved_pct.add(st.reflective ? 100.0 * double(st.curved) / double(st.reflective) : 0.0);
      traced_pct.add(100.0 * st.recompute_fraction());
    }
    ++since_key;
    diffuse_ms.add(diffuse);
    match_ms.add(st.match_ms);
    warp_ms.add(st.warp_ms);
    reproject_ms.add(st.reproject_ms);
    recompute_ms.add(st.recompute_ms);
    compose_ms.add(compose);
    temporal_ms.add(st.reflection_ms());
    frame_temporal_ms.add(diffuse + st.reflection_ms() + compose);

    double t_mae = NAN, d_mae = NAN, trace_ms = NAN;
    ImageF reference, direct_color;
    ImageU8 mask;
    if (run.compare) {
      // Full reflection ray tracing of the same frame: every reflective sample's rays.
      watch.restart();
      const TracedReflections traced = trace_reflections(scene, rays, frame);
      trace_ms = watch.elapsed_ms();
      reference = compose_reflections(frame, traced.radiance);
      reference_ms.add(trace_ms);
      frame_reference_ms.add(diffuse + trace_ms + compose);
      uint64_t direct_recomputed = 0;
      direct_color = compose_reflections(
          frame, direct_reprojection(scene, rays, frame, state.key, to.reproject, &direct_recomputed));
      mask = reflective_pixel_mask(frame);
      if (st.reflective > 0) {
        t_mae = compare_images(color, reference, &mask).mae_avg;
        d_mae = compare_images(direct_color, reference, &mask).mae_avg;
        temporal_mae.add(t_mae);
        direct_mae.add(d_mae);
        // Mirror pixels alone (g = 0): one ray each, no lobe noise between frames.
        ImageU8 mirror(camera.width, camera.height, 1, 0);
        size_t mirrors = 0;
        for (size_t i = 0; i < frame.sample_count(); ++i)
          if (frame.gloss[i] <= 0.0f) mirror.data()[frame.pixel[i]] = 1, ++mirrors;
        if (mirrors > 0) {
          mirror_temporal_mae.add(compare_images(color, reference, &mirror).mae_avg);
          mirror_direct_mae.add(compare_images(direct_color, reference, &mirror).mae_avg);
        }
        direct_recompute_pct.add(100.0 * double(direct_recomputed) / n);
      }
    }
    per_frame.rows.push_back({double(frame_index), st.key ? 1.0 : 0.0, reflective_pct.values.back(),
                              st.key ? 100.0 : 100.0 * st.recompute_fraction(), 100.0 * double(st.disoccluded) / n,
                              100.0 * double(st.unreliable) / n, t_mae, d_mae, diffuse, st.key_ms, st.match_ms,
                              st.warp_ms, st.reproject_ms, st.recompute_ms, compose, trace_ms});
    std::fprintf(stderr, "frame %d/%d: %s, recomputed %.1f%%, temporal %.0f ms%s\n", frame_index, frames,
                 st.key ? "key" : "reuse", 100.0 * st.recompute_fraction(), st.reflection_ms(),
                 run.compare ? (", trace " + std::to_string(int(trace_ms)) + " ms, mae " + std::to_string(t_mae) +
                                " (direct " + std::to_string(d_mae) + ")")
                                   .c_str()
                             : "");
    const bool image_here = tf.image_frame < 0 ? !st.key : tf.image_frame == frame_index;
    if (!wrote_images && image_here) {
      write_png_linear(out / "temporal.png", color);
      write_png_linear(out / "recompute.png", recompute_image(frame, flags, color));
      results.images["temporal"] = "temporal.png";
      results.images["recomputed_pixels"] = "recompute.png";
      if (run.compare) {
        write_png_linear(out / "reference.png", reference);
        write_png_linear(out / "direct.png", direct_color);
        write_png_linear(out / "error_temporal.png",
                         error_heatmap(error_image(color, reference, &mask), kHeatmapMax, &mask));
        write_png_linear(out / "error_direct.png",
                         error_heatmap(error_image(direct_color, reference, &mask), kHeatmapMax, &mask));
        results.images["reference"] = "reference.png";
        results.images["direct"] = "direct.png";
        results.images["error_temporal_0_20"] = "error_temporal.png";
        results.images["error_direct_0_20"] = "error_direct.png";
      }
      results.metrics["image_frame"] = double(frame_index);
      wrote_images = true;
    }
  }
  intervals.add(double(since_key));  // the last key frame's run, to the end of the path

  auto& m = results.metrics;
  m["frames"] = double(per_frame.rows.size());
  m["keyframes"] = double(keyframes);
  m["width"] = double(run.common.width);
  m["height"] = double(run.common.height);
  m["threshold"] = tf.threshold;
  m["spread_limit"] = tf.spread_limit;
  m["curved_contrast"] = tf.curved_contrast;
  m["reflective_pct_avg"] = reflective_pct.avg();
  m["reflective_pct_max"] = reflective_pct.max();
  m["recompute_pct_avg"] = recompute_pct.avg();  // non-key frames
  m["curved_pct_avg"] = curved_pct.avg();        // of those, on strongly curved reflectors
  m["traced_pct_avg"] = traced_pct.avg();        // every frame, key frames at 100%
  m["keyframe_interval_avg"] = intervals.avg();
  m["keyframe_interval_max"] = intervals.max();
  m["temporal_ms_avg"] = temporal_ms.avg();
  m["frame_temporal_ms_avg"] = frame_temporal_ms.avg();
  m["diffuse_ms_avg"] = diffuse_ms.avg();
  m["key_ms_avg"] = key_ms.avg();
  m["match_ms_avg"] = match_ms.avg();
  m["warp_ms_avg"] = warp_ms.avg();
  m["reproject_ms_avg"] = reproject_ms.avg();
  m["recompute_ms_avg"] = recompute_ms.avg();
  m["compose_ms_avg"] = compose_ms.avg();
  const std::string where = rest.name + " / " + path.name + " (" + std::to_string(run.common.width) + "x" +
                            std::to_string(run.common.height) + ")";
  if (run.compare) {
    m["temporal_mae_avg"] = temporal_mae.avg();
    m["temporal_mae_max"] = temporal_mae.max();
    m["direct_mae_avg"] = direct_mae.avg();
    m["direct_mae_max"] = direct_mae.max();
    m["direct_recompute_pct_avg"] = direct_recompute_pct.avg();
    m["temporal_mae_mirror_avg"] = mirror_temporal_mae.avg();
    m["direct_mae_mirror_avg"] = mirror_direct_mae.avg();
    m["reference_ms_avg"] = reference_ms.avg();
    m["frame_reference_ms_avg"] = frame_reference_ms.avg();
    m["speedup_vs_reference"] = temporal_ms.avg() > 0.0 ? reference_ms.avg() / temporal_ms.avg() : 0.0;
    m["frame_speedup_vs_reference"] =
        frame_temporal_ms.avg() > 0.0 ? frame_reference_ms.avg() / frame_temporal_ms.avg() : 0.0;
    results.tables.push_back(
        {"Frame rate (thesis Table 22), " + where,
         {"reflective_pct_max", "reflective_pct_avg", "reference_fps_max", "reference_fps_min", "reference_fps_avg",
          "temporal_fps_max", "temporal_fps_min", "temporal_fps_avg", "keyframe_interval_max",
          "keyframe_interval_avg", "recompute_pct"},
         {{reflective_pct.max(), reflective_pct.avg(), fps(frame_reference_ms.min()), fps(frame_reference_ms.max()),
           fps(frame_reference_ms.avg()), fps(frame_temporal_ms.min()), fps(frame_temporal_ms.max()),
           fps(frame_temporal_ms.avg()), intervals.max(), intervals.avg(), recompute_pct.avg()}}});
    results.tables.push_back({"Reflections: temporal vs direct reprojection vs full ray tracing, " + where,
                              {"temporal_mae_avg", "temporal_mae_max", "direct_mae_avg", "direct_mae_max",
                               "temporal_mae_mirror_avg", "direct_mae_mirror_avg", "temporal_reflection_ms_avg", "traced_reflection_ms_avg", "speedup_reflections",
                               "speedup_frames"},
                              {{temporal_mae.avg(), temporal_mae.max(), direct_mae.avg(), direct_mae.max(),
                                mirror_temporal_mae.avg(), mirror_direct_mae.avg(), temporal_ms.avg(), reference_ms.avg(), m["speedup_vs_reference"],
                                m["frame_speedup_vs_reference"]}}});
  }
  // Thesis Table 23: mean ms per step over all frames, and its share of the frame.
  const double total = frame_temporal_ms.avg() > 0.0 ? frame_temporal_ms.avg() : 1.0;
  Table steps{"Step times (thesis Table 23), " + where, {"step", "ms_avg", "pct"}, {}};
  auto step = [&](const char* name, double ms) { steps.rows.push_back({std::string(name), ms, 100.0 * ms / total}); };
  step("diffuse shading (G-buffer)", diffuse_ms.avg());
  step("key frame: trace all + reflection depth image", key_ms.values.empty() ? 0.0 : key_ms.avg() * double(keyframes) / double(per_frame.rows.size()));
  step("best match", match_ms.avg());
  step("reflection offset (warp)", warp_ms.avg());
  step("reprojection", reproject_ms.avg());
  step("recompute", recompute_ms.avg());
  step("composition", compose_ms.avg());
  step("total", frame_temporal_ms.avg());
  results.tables.push_back(steps);

  // Everything into results.json; the per-frame table is not printed.
  Results full = results;
  full.tables.push_back(per_frame);
  write_results_json(out / "results.json", full);
  for (const Table& t : results.tables) std::cout << markdown_table(t) << "\n";
  std::cout << "results: " << (out / "results.json").string() << "\n";
  return 0;
}

}  // namespace proxima::cli
