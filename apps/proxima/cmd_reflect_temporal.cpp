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
  if (!(t.edge_contrast >= 0.0f)) fail_input("--edge-contrast: must be ≥ 0 (inf = off)");
  if (!(t.blend_error >= 0.0f)) fail_input("--blend-error: must be ≥ 0 (inf = off)");
  if (!(t.keyframe_cost >= 0.0f && t.keyframe_cost < kInf)) fail_input("--keyframe-cost: must be finite and ≥ 0 (0 = off)");
  if (t.edge_rule != "nearest" && t.edge_rule != "recompute") fail_input("--edge-rule: must be nearest or recompute");
  if (t.image_frame < -1) fail_input("--image-frame: must be ≥ -1");
  if (!(t.depth_discontinuity > 0.0f) || !std::isfinite(t.depth_discontinuity))
    fail_input("--depth-discontinuity: must be > 0");
  if (!(t.lobe_seed_cell >= 0.0f && t.lobe_seed_cell <= 1.0f)) fail_input("--lobe-seed-cell: must be in [0, 1]");
  if (t.reference_rays < 0 || t.reference_rays > 1024) fail_input("--reference-rays: must be in 0..1024");
  if ((t.breakdown || t.reference_rays > 0) && !r.compare) fail_input("--breakdown / --reference-rays need --compare");
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


// --breakdown: where the temporal error sits. A reused pixel's class is its surface
// (curved or planar here × mirror or glossy) and where it lies: on the reflector's
// silhouette, next to a recomputed pixel (disocclusion / unreliable borders) or inside.
// Contributions are Σ error / reflective pixels per frame, averaged over all frames, so
// they add up to temporal_mae_avg.
constexpr int kSurfaces = 4, kPlaces = 3;
constexpr const char* kSurfaceNames[kSurfaces] = {"curved mirror", "curved glossy", "planar mirror", "planar glossy"};
constexpr const char* kPlaceNames[kPlaces] = {"inside", "reflector edge", "next to recomputed"};
constexpr int kClassKey = kSurfaces * kPlaces, kClassRecomputed = kClassKey + 1, kClassCount = kClassKey + 2;
std::string class_name(int c) {
  if (c == kClassKey) return "key frame";
  if (c == kClassRecomputed) return "recomputed";
  return std::string(kSurfaceNames[c / kPlaces]) + ", " + kPlaceNames[c % kPlaces];
}
// Neighbouring unit normals further apart than this (chord length) count as curved.
constexpr float kCurvedNormalChord = 1e-3f;

std::vector<uint8_t> error_classes(const ReflectionFrame& frame, bool key, const std::vector<uint8_t>& flags) {
  const size_t n = frame.sample_count();
  std::vector<uint8_t> cls(n, uint8_t(kClassKey));
  if (key) return cls;
  const int w = frame.camera.width, h = frame.camera.height;
  std::vector<int32_t> at(size_t(w) * size_t(h), -1);
  for (size_t i = 0; i < n; ++i) at[frame.pixel[i]] = int32_t(i);
  for (size_t i = 0; i < n; ++i) {
    if (flags[i] != kReuseOk) {
      cls[i] = uint8_t(kClassRecomputed);
      continue;
    }
    const int x = int(frame.pixel[i] % uint32_t(w)), y = int(frame.pixel[i] / uint32_t(w));
    bool edge = false, near = false, curved = false;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        const int32_t j = at[size_t(ny) * size_t(w) + size_t(nx)];
        const bool four = dx == 0 || dy == 0;
        if (j < 0 || frame.reflector[size_t(j)] != frame.reflector[i]) {
          edge = edge || four;
          continue;
        }
        near = near || flags[size_t(j)] != kReuseOk;
        if (four && glm::length(frame.normal[size_t(j)] - frame.normal[i]) > kCurvedNormalChord) curved = true;
      }
    const int surface = (curved ? 0 : 2) + (frame.gloss[i] > 0.0f ? 1 : 0);
    const int place = edge ? 1 : near ? 2 : 0;
    cls[i] = uint8_t(surface * kPlaces + place);
  }
  return cls;
}

// Per-class sums over the frames of a run.
struct ErrorBreakdown {
  double pixels[kClassCount] = {};      // Σ pixels
  double error[kClassCount] = {};       // Σ temporal error (0–255)
  double seed_error[kClassCount] = {};  // Σ error of the reference traced with another seed
  Series contribution[kClassCount];     // per frame Σ error / reflective pixels
  Series seed_contribution[kClassCount];

  void add(const ReflectionFrame& frame, const std::vector<uint8_t>& cls, const ImageF& per_pixel,
           const ImageF* seed_error_image) {
    double e[kClassCount] = {}, se[kClassCount] = {};
    for (size_t i = 0; i < frame.sample_count(); ++i) {
      const int c = cls[i];
      pixels[c] += 1.0;
      e[c] += per_pixel.data()[frame.pixel[i]];
      if (seed_error_image) se[c] += seed_error_image->data()[frame.pixel[i]];
    }
    const double n = std::max<double>(1.0, double(frame.sample_count()));
    for (int c = 0; c < kClassCount; ++c) {
      error[c] += e[c];
      seed_error[c] += se[c];
      contribution[c].add(e[c] / n);
      if (seed_error_image) seed_contribution[c].add(se[c] / n);
    }
  }
};

// Key-frame age (frames since the key frame) bins of the breakdown's second table.
constexpr int kAgeBins = 5;
constexpr int kAgeBinStart[kAgeBins] = {1, 3, 6, 11, 21};
int age_bin(int age) {
  int b = 0;
  while (b + 1 < kAgeBins && age >= kAgeBinStart[b + 1]) ++b;
  return b;
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
  app->add_option("--edge-contrast", f.edge_contrast,
                  "temporal: warped grid triangles whose corners' s*Lr differ by more than this (linear, any "
                  "channel) span an edge of the reflected image and follow --edge-rule; inf = off")
      ->capture_default_str();
  app->add_option("--edge-rule", f.edge_rule,
                  "temporal: on such an edge a reused pixel takes its nearest corner's Lr instead of a blend "
                  "(nearest) or is recomputed (recompute)")
      ->capture_default_str();
  app->add_flag("--recompute-splats", f.recompute_splats,
                "temporal: key samples no warp triangle reached (splatted as points) are unreliable, so recomputed");
  app->add_option("--blend-error", f.blend_error,
                  "temporal: a reused pixel whose expected display error (0-255: sum over the key samples it blends "
                  "of weight x |D(base + s*Lr_k) - D(base + s*value)|, D = sRGB, any channel) exceeds this is "
                  "recomputed; inf = off (the thesis' method; docs/temporal.md)")
      ->capture_default_str();
  app->add_option("--keyframe-cost", f.keyframe_cost,
                  "temporal: also start a key frame once a reuse frame's work (traced rays + this many rays per "
                  "reflective key pixel for best match, warp and reprojection) reaches the average work per frame "
                  "since the last key frame, full trace = 1; 0 = off (the thesis' threshold policy alone)")
      ->capture_default_str();
  app->add_flag("--match-extrapolate", f.match_extrapolate,
                "temporal: the best match also tries the previous offset plus its last change (steady motion) "
                "and starts from the closer of the two");
  app->add_option("--depth-discontinuity", f.depth_discontinuity,
                  "temporal: warp grid corners whose s.d or s.d + s.r differ by more than this fraction are not "
                  "connected (their gap is recomputed)")
      ->capture_default_str();
  app->add_option("--lobe-seed-cell", f.lobe_seed_cell,
                  "temporal: > 0 seeds glossy lobe rays by the surface point (world cell of this edge x the scene "
                  "diagonal) instead of the pixel, in the temporal method and the reference alike; 0 = per pixel")
      ->capture_default_str();
  app->add_flag("--breakdown", f.breakdown,
                "temporal, with --compare: error by pixel class and key-frame age, and the reference's own "
                "noise against itself traced with seed+1 (one more G-buffer and trace per frame)");
  app->add_option("--reference-rays", f.reference_rays,
                  "temporal, with --compare: also errors against a reference with this many glossy lobe rays "
                  "(0 = off)")
      ->capture_default_str();
}

int run_temporal_reflect(const TemporalReflectRun& run) {
  validate(run);
  const TemporalReflectFlags& tf = run.temporal;
  ThreadLimit limit(run.common.threads);
  const Scene rest = load_scene(run.common.scene);
  const int path_index = find_camera_path(rest, run.path);
  if (path_index < 0)
    fail_input("--path: scene '" + rest.name + "' has no camera path '" + run.path + "' (" +
               std::to_string(rest.camera_paths.size()) + " paths)");
  if (reflective_objects(rest).empty()) fail_input("--scene: '" + run.common.scene + "' has no reflective object");
  const CameraPath& path = rest.camera_paths[size_t(path_index)];
  const int frames = tf.frames > 0 ? tf.frames : path.frames;
  const auto out = prepare_out_dir(run.common.out);
  const float t_first = path.keys.front().time, t_last = path.keys.back().time;
  const float far = scene_far_plane(rest);
  const bool animated = has_animation(rest);

  ReflectionOptions ro;
  ro.supersample = 1;
  ro.glossy_rays = run.glossy_rays;
  ro.area_light_samples = run.light_samples;
  ro.seed = run.common.seed;
  ro.lobe_seed_cell = tf.lobe_seed_cell;
  TemporalOptions to;
  to.keyframe_threshold = tf.threshold;
  to.warp.stretch_limit = tf.stretch_limit;
  to.warp.spread_limit = tf.spread_limit;
  to.warp.curved_contrast = tf.curved_contrast;
  to.warp.edge_contrast = tf.edge_contrast;
  to.warp.recompute_splats = tf.recompute_splats;
  to.warp.blend_error = tf.blend_error;
  to.keyframe_cost = tf.keyframe_cost;
  to.warp.edge_rule = tf.edge_rule == "recompute" ? ReflectedEdgeRule::kRecompute : ReflectedEdgeRule::kNearest;
  to.warp.depth_discontinuity = tf.depth_discontinuity;
  to.match.extrapolate = tf.match_extrapolate;

  Scene scene = animated ? pose_scene(rest, t_first) : rest;
  RayScene rays(scene);
  TemporalState state;
  Series mirror_temporal_mae, mirror_direct_mae;
  Series reflective_pct, recompute_pct, traced_pct, temporal_mae, direct_mae, direct_recompute_pct, temporal_ms,
      reference_ms, frame_temporal_ms, frame_reference_ms, diffuse_ms, key_ms, match_ms, warp_ms, reproject_ms,
      recompute_ms, compose_ms, intervals, curved_pct, edge_pct, temporal_cpu_ms, reference_cpu_ms, match_steps;
  Table per_frame{"Per frame", {"frame", "key", "reflective_pct", "recompute_pct", "disoccluded_pct", "unreliable_pct",
                                "temporal_mae", "direct_mae", "diffuse_ms", "key_ms", "match_ms", "warp_ms",
                                "reproject_ms", "recompute_ms", "compose_ms", "reference_trace_ms"}, {}};
  Results results;
  results.command = command_line();
  results.threads = active_threads();
  bool wrote_images = false;
  int keyframes = 0, since_key = 0;
  ErrorBreakdown breakdown;
  Series age_mae[kAgeBins];
  Series hq_temporal_mae, hq_reference_mae, hq_direct_mae;
  std::vector<vec3> reflected;  // per frame; its memory (and flags') circulates with the state's
  std::vector<uint8_t> flags;
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
    double cpu = process_cpu_ms();
    temporal_reflections_into(scene, rays, frame, state, to, reflected, &st, &flags);
    temporal_cpu_ms.add(process_cpu_ms() - cpu);
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
      edge_pct.add(st.reflective ? 100.0 * double(st.edge) / double(st.reflective) : 0.0);
      match_steps.add(st.reflective ? double(st.match_steps) / double(st.reflective) : 0.0);
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
      const double trace_cpu = process_cpu_ms();
      const TracedReflections traced = trace_reflections(scene, rays, frame);
      reference_cpu_ms.add(process_cpu_ms() - trace_cpu);
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
        if (!st.key) age_mae[age_bin(state.frames_since_key)].add(t_mae);
        if (tf.breakdown) {
          // The reference against itself with another seed: the glossy lobe noise floor.
          ReflectionOptions other = ro;
          other.seed = ro.seed + 1;
          const ReflectionFrame f2 = prepare_reflection_frame(scene, camera, other);
          const ImageF ref2 = compose_reflections(f2, trace_reflections(scene, rays, f2).radiance);
          const ImageF seed_error = error_image(ref2, reference, &mask);
          breakdown.add(frame, error_classes(frame, st.key, flags), error_image(color, reference, &mask),
                        &seed_error);
        }
        if (tf.reference_rays > 0) {
          ReflectionOptions hq = ro;
          hq.glossy_rays = tf.reference_rays;
          hq.seed = ro.seed + 2;    // noise independent of the compared images' ...
          hq.lobe_seed_cell = 0.0f;  // ... and of their lobe seeding
          const ReflectionFrame fh = prepare_reflection_frame(scene, camera, hq);
          const ImageF ref_hq = compose_reflections(fh, trace_reflections(scene, rays, fh).radiance);
          hq_temporal_mae.add(compare_images(color, ref_hq, &mask).mae_avg);
          hq_reference_mae.add(compare_images(reference, ref_hq, &mask).mae_avg);
          hq_direct_mae.add(compare_images(direct_color, ref_hq, &mask).mae_avg);
        }
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
  m["lobe_seed_cell"] = tf.lobe_seed_cell;
  m["depth_discontinuity"] = tf.depth_discontinuity;
  m["reflective_pct_avg"] = reflective_pct.avg();
  m["reflective_pct_max"] = reflective_pct.max();
  m["recompute_pct_avg"] = recompute_pct.avg();  // non-key frames
  m["curved_pct_avg"] = curved_pct.avg();        // of those, on strongly curved reflectors
  m["edge_contrast"] = tf.edge_contrast;
  m["edge_rule_recompute"] = tf.edge_rule == "recompute" ? 1.0 : 0.0;
  m["recompute_splats"] = tf.recompute_splats ? 1.0 : 0.0;
  m["blend_error"] = tf.blend_error;
  m["keyframe_cost"] = tf.keyframe_cost;
  m["edge_pct_avg"] = edge_pct.avg();            // of those, on reflected edges (--edge-rule recompute)
  m["traced_pct_avg"] = traced_pct.avg();        // every frame, key frames at 100%
  m["keyframe_interval_avg"] = intervals.avg();
  m["keyframe_interval_max"] = intervals.max();
  m["temporal_ms_avg"] = temporal_ms.avg();
  m["frame_temporal_ms_avg"] = frame_temporal_ms.avg();
  m["diffuse_ms_avg"] = diffuse_ms.avg();
  m["key_ms_avg"] = key_ms.avg();
  m["match_ms_avg"] = match_ms.avg();
  m["match_extrapolate"] = tf.match_extrapolate ? 1.0 : 0.0;
  m["match_steps_per_pixel_avg"] = match_steps.avg();  // descent steps per reflective pixel, reuse frames
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
    // Process CPU time (both threads) of the two methods' reflection work: robust to load.
    m["temporal_cpu_ms_avg"] = temporal_cpu_ms.avg();
    m["reference_cpu_ms_avg"] = reference_cpu_ms.avg();
    m["speedup_cpu_vs_reference"] =
        temporal_cpu_ms.avg() > 0.0 ? reference_cpu_ms.avg() / temporal_cpu_ms.avg() : 0.0;
    m["speedup_cpu_median_ratio"] =
        median(temporal_cpu_ms.values) > 0.0 ? median(reference_cpu_ms.values) / median(temporal_cpu_ms.values) : 0.0;
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
  if (run.compare) {
    Table ages{"Temporal MAE by key-frame age (reuse frames), " + where, {"frames_since_key", "frames", "temporal_mae_avg"}, {}};
    for (int b = 0; b < kAgeBins; ++b) {
      const std::string label = b + 1 < kAgeBins ? std::to_string(kAgeBinStart[b]) + "-" + std::to_string(kAgeBinStart[b + 1] - 1)
                                                 : std::to_string(kAgeBinStart[b]) + "+";
      ages.rows.push_back({label, double(age_mae[b].values.size()), age_mae[b].avg()});
    }
    results.tables.push_back(ages);
  }
  if (tf.breakdown) {
    Table by_class{"Temporal error by pixel class, " + where,
                   {"class", "pixel_pct", "mae_in_class", "mae_contribution", "seed_noise_mae_in_class",
                    "seed_noise_contribution"},
                   {}};
    double all = 0.0;
    for (double p : breakdown.pixels) all += p;
    for (int c = 0; c < kClassCount; ++c) {
      const double p = std::max(1.0, breakdown.pixels[c]);
      by_class.rows.push_back({class_name(c), 100.0 * breakdown.pixels[c] / std::max(1.0, all),
                               breakdown.error[c] / p, breakdown.contribution[c].avg(), breakdown.seed_error[c] / p,
                               breakdown.seed_contribution[c].avg()});
      std::string key = class_name(c);
      key.erase(std::remove(key.begin(), key.end(), ','), key.end());
      std::replace(key.begin(), key.end(), ' ', '_');
      m["breakdown_" + key + "_mae_contribution"] = breakdown.contribution[c].avg();
    }
    double seed_total = 0.0;
    for (const Series& s : breakdown.seed_contribution) seed_total += s.avg();
    m["seed_noise_mae_avg"] = seed_total;
    results.tables.push_back(by_class);
  }
  if (tf.reference_rays > 0) {
    m["hq_temporal_mae_avg"] = hq_temporal_mae.avg();
    m["hq_reference_mae_avg"] = hq_reference_mae.avg();
    m["hq_direct_mae_avg"] = hq_direct_mae.avg();
    results.tables.push_back({"MAE against a reference with " + std::to_string(tf.reference_rays) +
                                  " glossy lobe rays, " + where,
                              {"temporal", "reference", "direct"},
                              {{hq_temporal_mae.avg(), hq_reference_mae.avg(), hq_direct_mae.avg()}}});
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
