// Study: temporal reuse of reflections (thesis ch. 5) along a camera path. With compare every
// frame is also fully ray traced (the reference, timed side by side) and rendered by direct
// depth reprojection of the same key frame.
#include "proxima/study/temporal_reflect.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/error.h"
#include "proxima/core/range_check.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/eval/series.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/reflect/temporal_reuse.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::study {

namespace {

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

// Breakdown: where the temporal error sits. A reused pixel's class is its surface (curved
// or planar here × mirror or glossy) and where it lies: on the reflector's silhouette, next
// to a recomputed pixel (disocclusion / unreliable borders) or inside. Contributions are
// Σ error / reflective pixels per frame, averaged over all frames, so they add up to
// temporal_mae_avg.
constexpr int kSurfaces = 4, kPlaces = 3;
constexpr const char* kSurfaceNames[kSurfaces] = {"curved mirror", "curved glossy", "planar mirror",
                                                  "planar glossy"};
constexpr const char* kPlaceNames[kPlaces] = {"inside", "reflector edge", "next to recomputed"};
constexpr int kClassKey = kSurfaces * kPlaces, kClassRecomputed = kClassKey + 1, kClassCount = kClassKey + 2;
std::string class_name(int c) {
  if (c == kClassKey) return "key frame";
  if (c == kClassRecomputed) return "recomputed";
  return std::string(kSurfaceNames[c / kPlaces]) + ", " + kPlaceNames[c % kPlaces];
}
// Neighbouring unit normals further apart than this (chord length) count as curved.
constexpr float kCurvedNormalChord = 1e-3f;

std::vector<uint8_t> error_classes(const ReflectionFrame& frame, bool key,
                                   const std::vector<uint8_t>& flags) {
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
        if (four && glm::length(frame.normal[size_t(j)] - frame.normal[i]) > kCurvedNormalChord)
          curved = true;
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

// Key-frame age (frames since the key frame) bins of the age table.
constexpr int kAgeBins = 5;
constexpr int kAgeBinStart[kAgeBins] = {1, 3, 6, 11, 21};
int age_bin(int age) {
  int b = 0;
  while (b + 1 < kAgeBins && age >= kAgeBinStart[b + 1]) ++b;
  return b;
}

// Everything a run accumulates over its frames.
struct TemporalSeries {
  Series mirror_temporal_mae, mirror_direct_mae;
  Series reflective_pct, recompute_pct, traced_pct, temporal_mae, direct_mae, direct_recompute_pct,
      temporal_ms, reference_ms, frame_temporal_ms, frame_reference_ms, diffuse_ms, key_ms, match_ms, warp_ms,
      reproject_ms, recompute_ms, compose_ms, intervals, curved_pct, edge_pct, refined_pct, learned_pct, temporal_cpu_ms,
      reference_cpu_ms, match_steps;
  Table per_frame{"Per frame",
                  {"frame", "key", "reflective_pct", "recompute_pct", "disoccluded_pct", "unreliable_pct",
                   "temporal_mae", "direct_mae", "diffuse_ms", "key_ms", "match_ms", "warp_ms",
                   "reproject_ms", "recompute_ms", "compose_ms", "reference_trace_ms"},
                  {}};
  int keyframes = 0, since_key = 0;
  ErrorBreakdown breakdown;
  Series age_mae[kAgeBins];
  Series hq_temporal_mae, hq_reference_mae, hq_direct_mae;
};

// One frame of the temporal method: the G-buffer and diffuse shading, the reuse, the blend.
struct TemporalFrame {
  ReflectionFrame frame;
  TemporalFrameStats st;
  ImageF color;
  double diffuse_ms = 0.0, compose_ms = 0.0;
};

// The temporal figures of a frame into the series.
void add_temporal(const TemporalFrame& f, TemporalSeries& s) {
  const TemporalFrameStats& st = f.st;
  s.reflective_pct.add(100.0 * double(st.reflective) / double(f.frame.camera.width * f.frame.camera.height));
  if (st.key) {
    if (s.keyframes > 0) s.intervals.add(double(s.since_key));
    ++s.keyframes;
    s.since_key = 0;
    s.key_ms.add(st.key_ms);
    s.traced_pct.add(st.reflective ? 100.0 : 0.0);
  } else {
    s.recompute_pct.add(100.0 * st.recompute_fraction());
    s.curved_pct.add(st.reflective ? 100.0 * double(st.curved) / double(st.reflective) : 0.0);
    s.edge_pct.add(st.reflective ? 100.0 * double(st.edge) / double(st.reflective) : 0.0);
    s.refined_pct.add(st.reflective ? 100.0 * double(st.refined) / double(st.reflective) : 0.0);
    s.learned_pct.add(st.reflective ? 100.0 * double(st.learned) / double(st.reflective) : 0.0);
    s.match_steps.add(st.reflective ? double(st.match_steps) / double(st.reflective) : 0.0);
    s.traced_pct.add(100.0 * st.recompute_fraction());
  }
  ++s.since_key;
  s.diffuse_ms.add(f.diffuse_ms);
  s.match_ms.add(st.match_ms);
  s.warp_ms.add(st.warp_ms);
  s.reproject_ms.add(st.reproject_ms);
  s.recompute_ms.add(st.recompute_ms);
  s.compose_ms.add(f.compose_ms);
  s.temporal_ms.add(st.reflection_ms());
  s.frame_temporal_ms.add(f.diffuse_ms + st.reflection_ms() + f.compose_ms);
}

// The compared images of a frame: full ray tracing and direct reprojection.
struct Comparison {
  ImageF reference, direct;
  ImageU8 mask;
  double trace_ms = NAN, temporal_mae = NAN, direct_mae = NAN;
};

// The reference traced from `options` (another seed or lobe count) on the frame's camera.
ImageF traced_image(const Scene& scene, const RayScene& rays, const Camera& camera,
                    const ReflectionOptions& options) {
  const ReflectionFrame f = prepare_reflection_frame(scene, camera, options);
  return compose_reflections(f, trace_reflections(scene, rays, f).radiance);
}

// The error figures of a compared frame with reflective pixels.
void add_errors(const Scene& scene, const RayScene& rays, const TemporalFrame& f,
                const std::vector<uint8_t>& flags, const TemporalState& state,
                const TemporalReflectOptions& o, const ReflectionOptions& ro, uint64_t direct_recomputed,
                Comparison& c, TemporalSeries& s) {
  const ReflectionFrame& frame = f.frame;
  c.temporal_mae = compare_images(f.color, c.reference, &c.mask).mae_avg;
  c.direct_mae = compare_images(c.direct, c.reference, &c.mask).mae_avg;
  s.temporal_mae.add(c.temporal_mae);
  s.direct_mae.add(c.direct_mae);
  // Mirror pixels alone (g = 0): one ray each, no lobe noise between frames.
  ImageU8 mirror(frame.camera.width, frame.camera.height, 1, 0);
  size_t mirrors = 0;
  for (size_t i = 0; i < frame.sample_count(); ++i)
    if (frame.gloss[i] <= 0.0f) mirror.data()[frame.pixel[i]] = 1, ++mirrors;
  if (mirrors > 0) {
    s.mirror_temporal_mae.add(compare_images(f.color, c.reference, &mirror).mae_avg);
    s.mirror_direct_mae.add(compare_images(c.direct, c.reference, &mirror).mae_avg);
  }
  s.direct_recompute_pct.add(100.0 * double(direct_recomputed) /
                             std::max<double>(1.0, double(f.st.reflective)));
  if (!f.st.key) s.age_mae[age_bin(state.frames_since_key)].add(c.temporal_mae);
  if (o.breakdown) {
    // The reference against itself with another seed: the glossy lobe noise floor.
    ReflectionOptions other = ro;
    other.seed = ro.seed + 1;
    const ImageF seed_error =
        error_image(traced_image(scene, rays, frame.camera, other), c.reference, &c.mask);
    s.breakdown.add(frame, error_classes(frame, f.st.key, flags), error_image(f.color, c.reference, &c.mask),
                    &seed_error);
  }
  if (o.reference_rays > 0) {
    ReflectionOptions hq = ro;
    hq.glossy_rays = o.reference_rays;
    hq.seed = ro.seed + 2;     // noise independent of the compared images' ...
    hq.lobe_seed_cell = 0.0f;  // ... and of their lobe seeding
    const ImageF ref_hq = traced_image(scene, rays, frame.camera, hq);
    s.hq_temporal_mae.add(compare_images(f.color, ref_hq, &c.mask).mae_avg);
    s.hq_reference_mae.add(compare_images(c.reference, ref_hq, &c.mask).mae_avg);
    s.hq_direct_mae.add(compare_images(c.direct, ref_hq, &c.mask).mae_avg);
  }
}

// Full reflection ray tracing of the same frame (every reflective sample's rays, timed, into
// `traced`, the previous frame's buffers as the key frames' trace has them) and direct
// reprojection of the current key frame; errors where the frame has reflective pixels.
Comparison compare_frame(const Scene& scene, const RayScene& rays, const TemporalFrame& f,
                         const std::vector<uint8_t>& flags, const TemporalState& state,
                         const TemporalOptions& to, const TemporalReflectOptions& o,
                         const ReflectionOptions& ro, TemporalSeries& s, TracedReflections& traced) {
  Comparison c;
  Stopwatch watch;
  const double trace_cpu = process_cpu_ms();
  trace_reflections_into(scene, rays, f.frame, traced);
  s.reference_cpu_ms.add(process_cpu_ms() - trace_cpu);
  c.trace_ms = watch.elapsed_ms();
  c.reference = compose_reflections(f.frame, traced.radiance);
  s.reference_ms.add(c.trace_ms);
  s.frame_reference_ms.add(f.diffuse_ms + c.trace_ms + f.compose_ms);
  uint64_t direct_recomputed = 0;
  c.direct = compose_reflections(
      f.frame, direct_reprojection(scene, rays, f.frame, state.key, to.reproject, &direct_recomputed));
  c.mask = reflective_pixel_mask(f.frame);
  if (f.st.reflective > 0) add_errors(scene, rays, f, flags, state, o, ro, direct_recomputed, c, s);
  return c;
}

void add_per_frame_row(int frame_index, const TemporalFrame& f, const Comparison& c, TemporalSeries& s) {
  const TemporalFrameStats& st = f.st;
  const double n = std::max<double>(1.0, double(st.reflective));
  s.per_frame.rows.push_back({double(frame_index), st.key ? 1.0 : 0.0, s.reflective_pct.values.back(),
                              st.key ? 100.0 : 100.0 * st.recompute_fraction(),
                              100.0 * double(st.disoccluded) / n, 100.0 * double(st.unreliable) / n,
                              c.temporal_mae, c.direct_mae, f.diffuse_ms, st.key_ms, st.match_ms, st.warp_ms,
                              st.reproject_ms, st.recompute_ms, f.compose_ms, c.trace_ms});
}

void write_images(const StudyOutput& out, const TemporalFrame& f, const std::vector<uint8_t>& flags,
                  const Comparison& c, bool compare, Results& results) {
  write_image(out, results, "temporal", "temporal.png", f.color);
  write_image(out, results, "recomputed_pixels", "recompute.png", recompute_image(f.frame, flags, f.color));
  if (!compare) return;
  write_image(out, results, "reference", "reference.png", c.reference);
  write_image(out, results, "direct", "direct.png", c.direct);
  write_image(out, results, "error_temporal", "error_temporal.png",
              error_heatmap(error_image(f.color, c.reference, &c.mask), kErrorHeatmapMax, &c.mask));
  write_image(out, results, "error_direct", "error_direct.png",
              error_heatmap(error_image(c.direct, c.reference, &c.mask), kErrorHeatmapMax, &c.mask));
}

void add_metrics(const TemporalReflectOptions& o, const TemporalSeries& s, Results& results) {
  auto& m = results.metrics;
  m["frames"] = double(s.per_frame.rows.size());
  m["keyframes"] = double(s.keyframes);
  m["width"] = double(o.width);
  m["height"] = double(o.height);
  m["threshold"] = o.threshold;
  m["spread_limit"] = o.spread_limit;
  m["curved_contrast"] = o.curved_contrast;
  m["lobe_seed_cell"] = o.lobe_seed_cell;
  m["depth_discontinuity"] = o.depth_discontinuity;
  m["reflective_pct_avg"] = s.reflective_pct.avg();
  m["reflective_pct_max"] = s.reflective_pct.max();
  m["recompute_pct_avg"] = s.recompute_pct.avg();  // non-key frames
  m["curved_pct_avg"] = s.curved_pct.avg();        // of those, on strongly curved reflectors
  m["edge_contrast"] = o.edge_contrast;
  m["edge_rule_recompute"] =
      parse_reflected_edge_rule(o.edge_rule, "--edge-rule") == ReflectedEdgeRule::kRecompute ? 1.0 : 0.0;
  m["recompute_splats"] = o.recompute_splats ? 1.0 : 0.0;
  m["blend_error"] = o.blend_error;
  m["keyframe_cost"] = o.keyframe_cost;
  m["edge_pct_avg"] = s.edge_pct.avg();      // of those, on reflected edges (--edge-rule recompute)
  m["refine_error"] = o.refine_error;
  m["refined_pct_avg"] = s.refined_pct.avg();  // of those, added by the refinement (--refine-error)
  m["learn_error"] = o.learn_error;
  m["learned_pct_avg"] = s.learned_pct.avg();  // of those, in key pixels marked by observed error (--learn-error)
  m["traced_pct_avg"] = s.traced_pct.avg();  // every frame, key frames at 100%
  m["keyframe_interval_avg"] = s.intervals.avg();
  m["keyframe_interval_max"] = s.intervals.max();
  m["temporal_ms_avg"] = s.temporal_ms.avg();
  m["frame_temporal_ms_avg"] = s.frame_temporal_ms.avg();
  m["diffuse_ms_avg"] = s.diffuse_ms.avg();
  m["key_ms_avg"] = s.key_ms.avg();
  m["match_ms_avg"] = s.match_ms.avg();
  m["match_extrapolate"] = o.match_extrapolate ? 1.0 : 0.0;
  m["match_steps_per_pixel_avg"] = s.match_steps.avg();  // descent steps per reflective pixel, reuse frames
  m["warp_ms_avg"] = s.warp_ms.avg();
  m["reproject_ms_avg"] = s.reproject_ms.avg();
  m["recompute_ms_avg"] = s.recompute_ms.avg();
  m["compose_ms_avg"] = s.compose_ms.avg();
}

void add_compare_metrics(const TemporalSeries& s, Results& results) {
  auto& m = results.metrics;
  m["temporal_mae_avg"] = s.temporal_mae.avg();
  m["temporal_mae_max"] = s.temporal_mae.max();
  m["direct_mae_avg"] = s.direct_mae.avg();
  m["direct_mae_max"] = s.direct_mae.max();
  m["direct_recompute_pct_avg"] = s.direct_recompute_pct.avg();
  m["temporal_mae_mirror_avg"] = s.mirror_temporal_mae.avg();
  m["direct_mae_mirror_avg"] = s.mirror_direct_mae.avg();
  m["reference_ms_avg"] = s.reference_ms.avg();
  m["frame_reference_ms_avg"] = s.frame_reference_ms.avg();
  m["speedup_vs_reference"] = s.temporal_ms.avg() > 0.0 ? s.reference_ms.avg() / s.temporal_ms.avg() : 0.0;
  // Process CPU time (both threads) of the two methods' reflection work: robust to load.
  m["temporal_cpu_ms_avg"] = s.temporal_cpu_ms.avg();
  m["reference_cpu_ms_avg"] = s.reference_cpu_ms.avg();
  m["speedup_cpu_vs_reference"] =
      s.temporal_cpu_ms.avg() > 0.0 ? s.reference_cpu_ms.avg() / s.temporal_cpu_ms.avg() : 0.0;
  m["speedup_cpu_median_ratio"] = median(s.temporal_cpu_ms.values) > 0.0
                                      ? median(s.reference_cpu_ms.values) / median(s.temporal_cpu_ms.values)
                                      : 0.0;
  m["frame_speedup_vs_reference"] =
      s.frame_temporal_ms.avg() > 0.0 ? s.frame_reference_ms.avg() / s.frame_temporal_ms.avg() : 0.0;
}

// A table of one row of numbers.
Table one_row(std::string title, std::vector<std::string> columns, const std::vector<double>& values) {
  Table t{std::move(title), std::move(columns), {}};
  t.rows.emplace_back(values.begin(), values.end());
  return t;
}

void add_compare_tables(const TemporalSeries& s, const std::string& where, Results& results) {
  const auto& m = results.metrics;
  results.tables.push_back(
      one_row("Frame rate (thesis Table 22), " + where,
              {"reflective_pct_max", "reflective_pct_avg", "reference_fps_max", "reference_fps_min",
               "reference_fps_avg", "temporal_fps_max", "temporal_fps_min", "temporal_fps_avg",
               "keyframe_interval_max", "keyframe_interval_avg", "recompute_pct"},
              {s.reflective_pct.max(), s.reflective_pct.avg(), fps(s.frame_reference_ms.min()),
               fps(s.frame_reference_ms.max()), fps(s.frame_reference_ms.avg()),
               fps(s.frame_temporal_ms.min()), fps(s.frame_temporal_ms.max()), fps(s.frame_temporal_ms.avg()),
               s.intervals.max(), s.intervals.avg(), s.recompute_pct.avg()}));
  results.tables.push_back(
      one_row("Reflections: temporal vs direct reprojection vs full ray tracing, " + where,
              {"temporal_mae_avg", "temporal_mae_max", "direct_mae_avg", "direct_mae_max",
               "temporal_mae_mirror_avg", "direct_mae_mirror_avg", "temporal_reflection_ms_avg",
               "traced_reflection_ms_avg", "speedup_reflections", "speedup_frames"},
              {s.temporal_mae.avg(), s.temporal_mae.max(), s.direct_mae.avg(), s.direct_mae.max(),
               s.mirror_temporal_mae.avg(), s.mirror_direct_mae.avg(), s.temporal_ms.avg(),
               s.reference_ms.avg(), m.at("speedup_vs_reference"), m.at("frame_speedup_vs_reference")}));
  Table ages{"Temporal MAE by key-frame age (reuse frames), " + where,
             {"frames_since_key", "frames", "temporal_mae_avg"},
             {}};
  for (int b = 0; b < kAgeBins; ++b) {
    const std::string label =
        b + 1 < kAgeBins ? std::to_string(kAgeBinStart[b]) + "-" + std::to_string(kAgeBinStart[b + 1] - 1)
                         : std::to_string(kAgeBinStart[b]) + "+";
    ages.rows.push_back({label, double(s.age_mae[b].values.size()), s.age_mae[b].avg()});
  }
  results.tables.push_back(ages);
}

void add_breakdown(const ErrorBreakdown& breakdown, const std::string& where, Results& results) {
  Table by_class{"Temporal error by pixel class, " + where,
                 {"class", "pixel_pct", "mae_in_class", "mae_contribution", "seed_noise_mae_in_class",
                  "seed_noise_contribution"},
                 {}};
  double all = 0.0;
  for (double p : breakdown.pixels) all += p;
  for (int c = 0; c < kClassCount; ++c) {
    const double p = std::max(1.0, breakdown.pixels[c]);
    by_class.rows.push_back({class_name(c), 100.0 * breakdown.pixels[c] / std::max(1.0, all),
                             breakdown.error[c] / p, breakdown.contribution[c].avg(),
                             breakdown.seed_error[c] / p, breakdown.seed_contribution[c].avg()});
    std::string key = class_name(c);
    key.erase(std::remove(key.begin(), key.end(), ','), key.end());
    std::replace(key.begin(), key.end(), ' ', '_');
    results.metrics["breakdown_" + key + "_mae_contribution"] = breakdown.contribution[c].avg();
  }
  double seed_total = 0.0;
  for (const Series& s : breakdown.seed_contribution) seed_total += s.avg();
  results.metrics["seed_noise_mae_avg"] = seed_total;
  results.tables.push_back(by_class);
}

void add_hq_reference(const TemporalSeries& s, int reference_rays, const std::string& where,
                      Results& results) {
  auto& m = results.metrics;
  m["hq_temporal_mae_avg"] = s.hq_temporal_mae.avg();
  m["hq_reference_mae_avg"] = s.hq_reference_mae.avg();
  m["hq_direct_mae_avg"] = s.hq_direct_mae.avg();
  results.tables.push_back(
      {"MAE against a reference with " + std::to_string(reference_rays) + " glossy lobe rays, " + where,
       {"temporal", "reference", "direct"},
       {{s.hq_temporal_mae.avg(), s.hq_reference_mae.avg(), s.hq_direct_mae.avg()}}});
}

// Thesis Table 23: mean ms per step over all frames, and its share of the frame.
void add_step_table(const TemporalSeries& s, const std::string& where, Results& results) {
  const double total = s.frame_temporal_ms.avg() > 0.0 ? s.frame_temporal_ms.avg() : 1.0;
  Table steps{"Step times (thesis Table 23), " + where, {"step", "ms_avg", "pct"}, {}};
  auto step = [&](const char* name, double ms) {
    steps.rows.push_back({std::string(name), ms, 100.0 * ms / total});
  };
  step("diffuse shading (G-buffer)", s.diffuse_ms.avg());
  step(
      "key frame: trace all + reflection depth image",
      s.key_ms.values.empty() ? 0.0 : s.key_ms.avg() * double(s.keyframes) / double(s.per_frame.rows.size()));
  step("best match", s.match_ms.avg());
  step("reflection offset (warp)", s.warp_ms.avg());
  step("reprojection", s.reproject_ms.avg());
  step("recompute", s.recompute_ms.avg());
  step("composition", s.compose_ms.avg());
  step("total", s.frame_temporal_ms.avg());
  results.tables.push_back(steps);
}

// Metrics and tables of the whole run; `where` names scene, path and size in the titles.
void add_results(const TemporalReflectOptions& o, const TemporalSeries& s, const std::string& where,
                 Results& results) {
  add_metrics(o, s, results);
  if (o.compare) {
    add_compare_metrics(s, results);
    add_compare_tables(s, where, results);
  }
  if (o.breakdown) add_breakdown(s.breakdown, where, results);
  if (o.reference_rays > 0) add_hq_reference(s, o.reference_rays, where, results);
  add_step_table(s, where, results);
  results.tables.push_back(s.per_frame);
}

// The temporal method on one frame: the G-buffer and the diffuse (non-reflected) shading,
// shared by both methods; the reuse; the blend. Its figures go into the series. `f` is the
// previous frame's, whose buffers the G-buffer pass reuses.
void render_frame(const Scene& scene, const RayScene& rays, const Camera& camera, const ReflectionOptions& ro,
                  const TemporalOptions& to, TemporalState& state, std::vector<vec3>& reflected,
                  std::vector<uint8_t>& flags, TemporalSeries& s, TemporalFrame& f) {
  Stopwatch watch;
  prepare_reflection_frame_into(scene, camera, ro, f.frame);
  f.diffuse_ms = watch.elapsed_ms();
  const double cpu = process_cpu_ms();
  temporal_reflections_into(scene, rays, f.frame, state, to, reflected, &f.st, &flags);
  s.temporal_cpu_ms.add(process_cpu_ms() - cpu);
  watch.restart();
  compose_reflections_into(f.frame, reflected, f.color);
  f.compose_ms = watch.elapsed_ms();
  add_temporal(f, s);
}

}  // namespace

ReflectionOptions reflection_options(const TemporalReflectOptions& o) {
  ReflectionOptions ro;
  ro.supersample = 1;
  ro.glossy_rays = o.glossy_rays;
  ro.area_light_samples = o.light_samples;
  ro.seed = o.seed;
  ro.lobe_seed_cell = o.lobe_seed_cell;
  return ro;
}

TemporalOptions temporal_options(const TemporalReflectOptions& o) {
  TemporalOptions to;
  to.keyframe_threshold = o.threshold;
  to.warp.stretch_limit = o.stretch_limit;
  to.warp.spread_limit = o.spread_limit;
  to.warp.curved_contrast = o.curved_contrast;
  to.warp.edge_contrast = o.edge_contrast;
  to.warp.recompute_splats = o.recompute_splats;
  to.warp.blend_error = o.blend_error;
  to.keyframe_cost = o.keyframe_cost;
  to.refine_error = o.refine_error;
  to.learn_error = o.learn_error;
  to.warp.edge_rule = parse_reflected_edge_rule(o.edge_rule, "--edge-rule");
  to.warp.depth_discontinuity = o.depth_discontinuity;
  to.match.extrapolate = o.match_extrapolate;
  return to;
}

void validate(const TemporalReflectOptions& o) {
  require_in_range(o.width, 1, kMaxImageSide, "--width");
  require_in_range(o.height, 1, kMaxImageSide, "--height");
  if (o.path.empty()) fail_input("--path: --method temporal needs a camera path (index or name)");
  require_in_range(o.light_samples, 1, 64, "--light-samples");
  require_in_range(o.glossy_rays, 1, 1024, "--glossy-rays", "for --method temporal");
  require_in_range(o.frames, 0, 100000, "--frames");
  require_in_range(o.frame_step, 1, 100000, "--frame-step");
  require_in_range(o.threshold, 0.0f, 1.0f, "--threshold");
  if (!(o.stretch_limit >= 1.0f) || !std::isfinite(o.stretch_limit))
    fail_input("--stretch-limit: must be ≥ 1");
  require_at_least(o.spread_limit, 1.0f, "--spread-limit", "(inf = off)");
  require_at_least(o.curved_contrast, 0.0f, "--curved-contrast");
  require_at_least(o.edge_contrast, 0.0f, "--edge-contrast", "(inf = off)");
  require_at_least(o.blend_error, 0.0f, "--blend-error", "(inf = off)");
  require_at_least(o.refine_error, 0.0f, "--refine-error", "(inf = off)");
  require_at_least(o.learn_error, 0.0f, "--learn-error", "(inf = off)");
  if (!(o.keyframe_cost >= 0.0f && o.keyframe_cost < kInf))
    fail_input("--keyframe-cost: must be finite and ≥ 0 (0 = off)");
  parse_reflected_edge_rule(o.edge_rule, "--edge-rule");
  require_at_least(o.image_frame, -1, "--image-frame");
  if (!(o.depth_discontinuity > 0.0f) || !std::isfinite(o.depth_discontinuity))
    fail_input("--depth-discontinuity: must be > 0");
  require_in_range(o.lobe_seed_cell, 0.0f, 1.0f, "--lobe-seed-cell");
  require_in_range(o.reference_rays, 0, 1024, "--reference-rays");
  if ((o.breakdown || o.reference_rays > 0) && !o.compare)
    fail_input("--breakdown / --reference-rays need --compare");
}

void validate(const TemporalReflectOptions& o, const Scene& scene) {
  camera_path(scene, o.path);
  if (reflective_objects(scene).empty()) fail_input("--scene: '" + scene.name + "' has no reflective object");
}

Results run_temporal_reflect(const Scene& rest, const TemporalReflectOptions& o, const StudyOutput& out,
                             Progress* progress) {
  validate(o);
  validate(o, rest);
  const CameraPath& path = camera_path(rest, o.path);
  const int frames = o.frames > 0 ? o.frames : path.frames;
  const float t_first = path.keys.front().time, t_last = path.keys.back().time;
  const float far = scene_far_plane(rest);
  const bool animated = has_animation(rest);
  const ReflectionOptions ro = reflection_options(o);
  const TemporalOptions to = temporal_options(o);

  Scene scene = animated ? pose_scene(rest, t_first) : rest;
  RayScene rays(scene);
  TemporalState state;
  TemporalSeries s;
  Results results;
  bool wrote_images = false;
  std::vector<vec3> reflected;  // per frame; its memory (and flags') circulates with the state's
  std::vector<uint8_t> flags;
  if (progress) progress->begin("reflect temporal", (frames + o.frame_step - 1) / o.frame_step);
  TemporalFrame f;                    // one frame's buffers for the whole path
  TracedReflections reference_trace;  // the same for the full trace
  for (int frame_index = 0; frame_index < frames; frame_index += o.frame_step) {
    if (progress) progress->step("frame " + std::to_string(frame_index) + "/" + std::to_string(frames));
    const float t =
        frames > 1 ? t_first + float(frame_index) * (t_last - t_first) / float(frames - 1) : t_first;
    if (animated) {
      // Reuse assumes a static scene (thesis §5.5.4); moving parts are posed but reused as is.
      scene = pose_scene(rest, t);
      rays.update(scene);
    }
    const Camera camera = camera_at_time(path, t, o.width, o.height, 0.01f, far);

    render_frame(scene, rays, camera, ro, to, state, reflected, flags, s, f);
    const Comparison c =
        o.compare ? compare_frame(scene, rays, f, flags, state, to, o, ro, s, reference_trace) : Comparison{};
    add_per_frame_row(frame_index, f, c, s);
    const bool image_here = o.image_frame < 0 ? !f.st.key : o.image_frame == frame_index;
    if (!wrote_images && image_here) {
      write_images(out, f, flags, c, o.compare, results);
      results.metrics["image_frame"] = double(frame_index);
      wrote_images = true;
    }
  }
  if (progress) progress->end();
  s.intervals.add(double(s.since_key));  // the last key frame's run, to the end of the path

  add_results(
      o, s,
      rest.name + " / " + path.name + " (" + std::to_string(o.width) + "x" + std::to_string(o.height) + ")",
      results);
  return results;
}

}  // namespace proxima::study
