// Study: reflections from screen-space clustered depth images (thesis ch. 4) on one camera
// or along a camera path, optionally compared with Embree tracing the same rays and with
// rectified environment mapping on the same rays.
#include "proxima/study/cluster_reflect.h"

#include <algorithm>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/range_check.h"
#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/eval/series.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/box_probe.h"
#include "proxima/reflect/envmap_frame_reflections.h"
#include "proxima/reflect/envmap_lookup.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/reflect/envmap_set.h"
#include "proxima/reflect/hit_shading.h"
#include "proxima/reflect/ssr_reflection.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/shading.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::study {

namespace {

const char* const kCauseNames[kOcclusionCauses] = {"none", "behind_near_plane", "outside_image",
                                                   "own_curved_reflector", "hidden_in_image"};
// Metric names of the SsrOutcome values.
const char* const kSsrOutcomeNames[5] = {"hit", "hidden", "offscreen", "step_limit", "exhausted"};

// Output-resolution image of the samples: per sample the color `of(i)`, over a dimmed `color`
// (each of a pixel's k×k samples covers its share).
template <typename SampleColor>
ImageF sample_overlay(const ReflectionFrame& frame, const ImageF& color, SampleColor&& of) {
  ImageF out = color;
  for (float& v : out.data()) v *= 0.3f;
  const int sw = frame.sample_camera.width, k = frame.supersample;
  const float share = 1.0f / float(k * k);
  for (size_t i = 0; i < frame.sample_count(); ++i) {
    const vec3 c = of(i);
    const int x = int(frame.pixel[i] % uint32_t(sw)) / k, y = int(frame.pixel[i] / uint32_t(sw)) / k;
    for (int ch = 0; ch < 3; ++ch) out.at(x, y, ch) += share * (c[ch] - 0.3f * color.at(x, y, ch));
  }
  return out;
}

// Clusters in hashed colors, flagged samples red (environment fallback) and yellow
// (occlusion error).
ImageF cluster_image(const ReflectionFrame& frame, const ClusterReflections& cr, const ImageF& color) {
  return sample_overlay(frame, color, [&](size_t i) {
    uint64_t h = mix64(cr.cluster[i]);
    vec3 c(float(h & 255) / 255.0f, float((h >> 8) & 255) / 255.0f, float((h >> 16) & 255) / 255.0f);
    if (cr.flags[i] & kEnvFallback) c = vec3(1, 0, 0);
    if (cr.flags[i] & kOcclusionError) c = vec3(1, 1, 0);
    return c;
  });
}

// The SSR fallback: red by the share of a sample's rays' radiance that came from the
// fallback (1 − confidence), blue where SSR answered alone.
ImageF ssr_fallback_image(const ReflectionFrame& frame, const SsrReflections& ssr, const ImageF& color) {
  return sample_overlay(frame, color, [&](size_t i) {
    const float fb = 1.0f - ssr.confidence[i];
    return fb * vec3(1, 0, 0) + (1.0f - fb) * vec3(0.2f, 0.6f, 1.0f);
  });
}

// The frames to render: one (the scene camera --camera, or --path with --frame), or the
// path divided into --frames frames, every --frame-step-th rendered.
struct Schedule {
  const CameraPath* path = nullptr;
  int frames = 1;
  bool sequence = false;  // frames of the path, posed by time
  std::vector<int> indices;

  float time_of(int index) const {
    if (!path) return 0.0f;
    if (!sequence) return frame_time(*path, index);
    const float t0 = path->keys.front().time, t1 = path->keys.back().time;
    return frames > 1 ? t0 + float(index) * (t1 - t0) / float(frames - 1) : t0;
  }
};

Schedule schedule(const Scene& scene, const ClusterReflectOptions& o) {
  Schedule s;
  if (!o.camera.path.empty()) {
    s.path = &camera_path(scene, o.camera.path);
    s.frames = o.frames > 0 ? o.frames : s.path->frames;
  }
  s.sequence = s.path && !o.frame_given;
  if (s.sequence) {
    for (int i = 0; i < s.frames; i += o.frame_step) s.indices.push_back(i);
  } else {
    s.indices.push_back(o.frame_given ? o.camera.frame : 0);
  }
  return s;
}

// Per-frame figures of the run, reduced in the tables.
struct ClusterSeries {
  Series reflective_pct, cluster_ms, reference_ms, reference_dynamic_ms, envmap_ms, envmap_build_ms, step1_ms,
      cameras_ms, images_ms, intersection_ms, clusters, samples_per_cluster, occlusion_pct, fallback_pct,
      planar_pct, mae_r, mae_g, mae_b, env_r, env_g, env_b, texels, fill_pct, occlusion_ray_pct,
      occlusion_mirror_pct, occlusion_glossy_pct, full_r, full_g, full_b, traced_full, second_texels,
      second_ray_pct, cluster_cpu_ms, reference_cpu_ms, reference_dynamic_cpu_ms, step1_cpu_ms, cameras_cpu_ms,
      images_cpu_ms, intersection_cpu_ms, texel_shading_ms, triangles_drawn, shaded_texels, own_texels,
      own_ray_pct, own_exact_cpu_ms;
  Series cause_pct[kOcclusionCauses], cause_mirror_pct[kOcclusionCauses];
  // SSR and the box probe alone (ssr).
  Series ssr_ms, box_ms, ssr_r, ssr_g, ssr_b, box_r, box_g, box_b, ssr_fallback_pct, ssr_fallback_rays_pct,
      ssr_steps, ssr_confidence, ssr_outcome_pct[5], ssr_depth_ms, ssr_trace_ms;
  Series envmap_groups, probe_build_ms;  // the comparison's maps; ssr: the box probe's map build
};

// One frame of both methods (and the comparison's), with the median times of its reps.
struct FrameRun {
  ReflectionFrame frame;
  ClusterReflections cluster;
  TracedReflections traced;
  std::unique_ptr<RayScene> rays;
  std::vector<vec3> env_radiance;
  SsrReflections ssr;               // ssr: SSR with the box-probe fallback
  std::vector<vec3> box_radiance;   // ssr: the box probe alone on every ray
  double ssr_ms = 0.0, box_ms = 0.0;
  double cluster_ms = 0.0, step1_ms = 0.0, cameras_ms = 0.0, images_ms = 0.0, intersection_ms = 0.0;
  double reference_ms = 0.0, build_ms = 0.0, envmap_ms = 0.0, envmap_build_ms = 0.0, envmap_groups = 0.0;
  double probe_build_ms = 0.0;  // ssr: the box probe's map
  // Process CPU time (all threads) of the same steps: steadier than wall-clock under load.
  double cluster_cpu_ms = 0.0, step1_cpu_ms = 0.0, cameras_cpu_ms = 0.0, images_cpu_ms = 0.0,
         intersection_cpu_ms = 0.0, texel_shading_ms = 0.0, reference_cpu_ms = 0.0, build_cpu_ms = 0.0;
};

// The env map of the reflectors' environment from their common centre, texels shaded as the
// cluster images' (unshadowed); built once per frame (the scene moves).
DistanceCubeMapOptions environment_map_options(const Scene& scene, const ClusterReflectOptions& o,
                                               const ReflectionOptions& ro) {
  DistanceCubeMapOptions mo;
  mo.resolution = o.cube_size;
  mo.area_light_samples = ro.area_light_samples;
  mo.seed = ro.seed;
  mo.shade = [&scene, n = ro.area_light_samples](uint32_t tri, float u, float v, vec3 toward) {
    return shade_reflected_point(scene, tri, u, v, toward, n);
  };
  return mo;
}

// The comparison's env maps, one per group of reflectors (envmap_set.h), texels shaded as the
// cluster images' (shade_reflected_point) so both methods show the same surfaces' colors.
EnvmapSet environment_maps(const Scene& scene, const RayScene& rays, const ClusterReflectOptions& o,
                           const ReflectionOptions& ro) {
  EnvmapSetOptions so;
  so.grouping = o.envmap_groups;
  so.map = environment_map_options(scene, o, ro);
  return build_envmap_set(scene, rays, reflective_objects(scene), so);
}

// The box probe's map: one for the room, around the center of every reflector with all of
// them left out, shaded as above.
DistanceCubeMap probe_map(const Scene& scene, const RayScene& rays, const ClusterReflectOptions& o,
                          const ReflectionOptions& ro) {
  const std::vector<uint32_t> reflectors = reflective_objects(scene);
  DistanceCubeMapOptions mo = environment_map_options(scene, o, ro);
  mo.exclude = reflectors;
  return render_distance_cube_map(scene, rays, projection_center(scene, reflectors), mo);
}

// SSR and the box probe alone on the frame's rays, timed from the shared G-buffer step on.
void run_ssr(const Scene& scene, const ClusterReflectOptions& o, const DistanceCubeMap& map,
             std::span<const Bounds3> bounds, double step1, FrameRun& f, std::vector<double>& ssr_ms,
             std::vector<double>& box_ms) {
  EnvmapInputs probe;
  probe.method = EnvmapMethod::BoxProbe;
  probe.map = &map;
  probe.box = probe_proxy_box(scene);
  Stopwatch w;
  f.ssr = render_ssr_reflections(scene, f.frame, o.ssr_options, {&map, probe.box}, bounds);
  ssr_ms.push_back(step1 + w.elapsed_ms());
  w.restart();
  f.box_radiance = envmap_frame_reflections(scene, f.frame, probe);
  box_ms.push_back(step1 + w.elapsed_ms());
}

// Side by side, `reps` times; medians per frame.
FrameRun run_frame(const Scene& scene, const Camera& camera, const ClusterReflectOptions& o,
                   const ReflectionOptions& ro) {
  FrameRun f;
  std::vector<double> c_ms, r_ms, b_ms, e_ms, s1, s2, s3, s4, c_cpu, r_cpu, b_cpu, s1_cpu, s2_cpu, s3_cpu, s4_cpu,
      shading, ssr_ms, box_ms;
  EnvmapSet maps;
  DistanceCubeMap probe;
  const DistanceCubeMap* probe_used = &probe;
  EnvmapInputs rectified;
  rectified.method = EnvmapMethod::Rectified;
  rectified.rectify.D = o.distance > 0.0f ? o.distance : scene_bounds(scene).diagonal();
  rectified.rectify.d_e = o.d_e;
  rectified.rectify.edge = o.edge_fallback ? EdgeRule::PlainFallback : EdgeRule::Black;
  for (int rep = 0; rep < o.reps; ++rep) {
    Stopwatch watch;
    double cpu = process_cpu_ms();
    const std::vector<Bounds3> bounds = raster_object_bounds(scene);
    prepare_reflection_frame_into(scene, camera, ro, f.frame, bounds);  // the last repetition's buffers
    const double step1 = watch.elapsed_ms(), step1_cpu = process_cpu_ms() - cpu;
    if (o.compare) {
      cpu = process_cpu_ms();
      f.rays = std::make_unique<RayScene>(scene);
      b_cpu.push_back(process_cpu_ms() - cpu);
      b_ms.push_back(f.rays->build_ms());
      cpu = process_cpu_ms();
      trace_reflections_into(scene, *f.rays, f.frame, f.traced);
      r_cpu.push_back(step1_cpu + process_cpu_ms() - cpu);
      r_ms.push_back(step1 + f.traced.ms);
      if (rep == 0) {
        Stopwatch w;
        maps = environment_maps(scene, *f.rays, o, ro);
        f.envmap_build_ms = w.elapsed_ms();
        f.envmap_groups = double(maps.groups.size());
      }
      Stopwatch w;
      f.env_radiance = envmap_frame_reflections(scene, f.frame, with_envmap_set(rectified, maps));
      e_ms.push_back(step1 + w.elapsed_ms());
    }
    if (o.ssr && rep == 0) {
      // The fallback's map: the comparison's when it is one map for every reflector (the same
      // map), else its own; without compare nothing else needs the rays.
      if (!o.compare) f.rays = std::make_unique<RayScene>(scene);
      if (o.compare && maps.groups.size() == 1) {
        probe_used = &maps.maps[0].map;
        f.probe_build_ms = f.envmap_build_ms;
      } else {
        Stopwatch w;
        probe = probe_map(scene, *f.rays, o, ro);
        f.probe_build_ms = w.elapsed_ms();
      }
    }
    if (o.ssr) run_ssr(scene, o, *probe_used, bounds, step1, f, ssr_ms, box_ms);
    f.cluster =
        render_cluster_reflections(scene, f.frame, o.cluster, bounds, o.compare ? &f.traced : nullptr);
    const ClusterFrameStats& st = f.cluster.stats;
    s1.push_back(step1 + st.clustering_ms);
    s2.push_back(st.cameras_ms);
    s3.push_back(st.depth_images_ms);
    s4.push_back(st.intersection_ms);
    c_ms.push_back(s1.back() + s2.back() + s3.back() + s4.back());
    s1_cpu.push_back(step1_cpu + st.clustering_cpu_ms);
    s2_cpu.push_back(st.cameras_cpu_ms);
    s3_cpu.push_back(st.depth_images_cpu_ms);
    s4_cpu.push_back(st.intersection_cpu_ms);
    c_cpu.push_back(s1_cpu.back() + s2_cpu.back() + s3_cpu.back() + s4_cpu.back());
    shading.push_back(st.texel_shading_ms);
  }
  f.cluster_cpu_ms = median(c_cpu);
  f.step1_cpu_ms = median(s1_cpu);
  f.cameras_cpu_ms = median(s2_cpu);
  f.images_cpu_ms = median(s3_cpu);
  f.intersection_cpu_ms = median(s4_cpu);
  f.texel_shading_ms = median(shading);
  f.cluster_ms = median(c_ms);
  f.step1_ms = median(s1);
  f.cameras_ms = median(s2);
  f.images_ms = median(s3);
  f.intersection_ms = median(s4);
  if (o.ssr) {
    f.ssr_ms = median(ssr_ms);
    f.box_ms = median(box_ms);
  }
  if (o.compare) {
    f.reference_ms = median(r_ms);
    f.build_ms = median(b_ms);
    f.envmap_ms = median(e_ms);
    f.reference_cpu_ms = median(r_cpu);
    f.build_cpu_ms = median(b_cpu);
  }
  return f;
}

// Occlusion-error figures of a compared frame with reflective pixels: totals, and causes
// over all reflective samples and over the mirror samples (one ray each).
void add_occlusion_errors(const FrameRun& f, double samples, ClusterSeries& s) {
  const ClusterFrameStats& st = f.cluster.stats;
  s.occlusion_pct.add(100.0 * double(st.occlusion_error_samples) / samples);
  s.occlusion_ray_pct.add(100.0 * double(st.occlusion_error_rays) / std::max<double>(1.0, double(st.rays)));
  uint64_t mirror_cause[kOcclusionCauses] = {}, glossy_errors = 0;
  for (size_t i = 0; i < f.frame.sample_count(); ++i) {
    const bool mirror = glossy_lobe_half_angle(f.frame.gloss[i]) <= 0.0f;
    if (mirror)
      ++mirror_cause[f.cluster.occlusion_cause[i]];
    else
      glossy_errors += f.cluster.occlusion_cause[i] != uint8_t(OcclusionCause::None);
  }
  for (int c = 1; c < kOcclusionCauses; ++c) {
    s.cause_pct[c].add(100.0 * double(st.occlusion_cause_samples[c]) / samples);
    if (st.mirror_samples > 0)
      s.cause_mirror_pct[c].add(100.0 * double(mirror_cause[c]) / double(st.mirror_samples));
  }
  if (st.mirror_samples > 0)
    s.occlusion_mirror_pct.add(100.0 * double(st.mirror_occlusion_error_samples) / double(st.mirror_samples));
  if (st.mirror_samples < st.reflective_samples)
    s.occlusion_glossy_pct.add(100.0 * double(glossy_errors) /
                               double(st.reflective_samples - st.mirror_samples));
}

// Ground truth with shadows and jittered area-light samples; the Embree pass on the same
// rays against it isolates what the shared unshadowed shading costs.
void add_full_reference_errors(const Scene& scene, const FrameRun& f, const Camera& camera,
                               const ReflectionOptions& ro, const ImageF& color, const ImageF& reference,
                               const ImageU8& mask, ClusterSeries& s) {
  ReferenceOptions full_opts;
  full_opts.supersample = ro.supersample;
  full_opts.area_light_samples = ro.area_light_samples;
  full_opts.glossy_rays = ro.glossy_rays;
  full_opts.max_bounces = 1;
  full_opts.seed = ro.seed;
  const ImageF full = render_reference(scene, *f.rays, camera, full_opts);
  const ImageError cluster_err = compare_images(color, full, &mask);
  s.full_r.add(cluster_err.mae[0]);
  s.full_g.add(cluster_err.mae[1]);
  s.full_b.add(cluster_err.mae[2]);
  s.traced_full.add(compare_images(reference, full, &mask).mae_avg);
}

// SSR figures of a frame: times (every frame), and where it has reflective samples the
// fallback shares, outcome shares, steps and confidence.
void add_ssr_frame(const FrameRun& f, ClusterSeries& s) {
  const SsrStats& st = f.ssr.stats;
  s.ssr_ms.add(f.ssr_ms);
  s.box_ms.add(f.box_ms);
  s.probe_build_ms.add(f.probe_build_ms);
  s.ssr_depth_ms.add(st.gbuffer_ms + st.backface_ms + st.pyramid_ms);
  s.ssr_trace_ms.add(st.trace_ms);
  if (st.samples == 0) return;
  const double rays = double(std::max<size_t>(1, st.rays));
  s.ssr_fallback_pct.add(100.0 * double(st.fallback_samples) / double(st.samples));
  s.ssr_fallback_rays_pct.add(100.0 * double(st.fallback_rays) / rays);
  for (int k = 0; k < 5; ++k) s.ssr_outcome_pct[k].add(100.0 * double(st.outcome_rays[k]) / rays);
  s.ssr_steps.add(double(st.steps) / rays);
  s.ssr_confidence.add(st.confidence_sum / rays);
}

// The frame's figures into the series. Cluster figures average over the frames that show
// reflective pixels, and so do the error figures.
void add_frame(const FrameRun& f, size_t reflective, size_t pixels, bool compare, ClusterSeries& s) {
  const ClusterFrameStats& st = f.cluster.stats;
  const double samples = std::max<double>(1.0, double(st.reflective_samples));
  s.reflective_pct.add(100.0 * double(reflective) / double(pixels));
  s.cluster_ms.add(f.cluster_ms);
  s.step1_ms.add(f.step1_ms);
  s.cameras_ms.add(f.cameras_ms);
  s.images_ms.add(f.images_ms);
  s.intersection_ms.add(f.intersection_ms);
  s.cluster_cpu_ms.add(f.cluster_cpu_ms);
  s.step1_cpu_ms.add(f.step1_cpu_ms);
  s.cameras_cpu_ms.add(f.cameras_cpu_ms);
  s.images_cpu_ms.add(f.images_cpu_ms);
  s.intersection_cpu_ms.add(f.intersection_cpu_ms);
  s.texel_shading_ms.add(f.texel_shading_ms);
  if (reflective > 0) {
    s.triangles_drawn.add(double(st.triangles_drawn));
    s.shaded_texels.add(double(st.shaded_texels));
    s.clusters.add(double(st.clusters));
    s.texels.add(double(st.texels));
    s.second_texels.add(double(st.second_layer_texels));
    s.second_ray_pct.add(100.0 * double(st.second_layer_rays) / std::max<double>(1.0, double(st.rays)));
    s.own_texels.add(double(st.own_layer_texels));
    s.own_ray_pct.add(100.0 * double(st.own_layer_rays) / std::max<double>(1.0, double(st.rays)));
    s.own_exact_cpu_ms.add(st.own_exact_cpu_ms);
    s.samples_per_cluster.add(double(st.reflective_samples) / double(st.clusters));
    s.planar_pct.add(100.0 * double(st.planar_samples) / samples);
  }
  s.fallback_pct.add(100.0 * double(st.env_fallback_samples) / samples);
  s.fill_pct.add(100.0 * double(st.behind_fill_samples) / samples);
  if (compare) {
    s.reference_ms.add(f.reference_ms);
    s.reference_dynamic_ms.add(f.reference_ms + f.build_ms);
    s.envmap_ms.add(f.envmap_ms);
    s.envmap_build_ms.add(f.envmap_build_ms);
    s.envmap_groups.add(f.envmap_groups);
    s.reference_cpu_ms.add(f.reference_cpu_ms);
    s.reference_dynamic_cpu_ms.add(f.reference_cpu_ms + f.build_cpu_ms);
  }
}

void add_mae(const ImageError& e, Series& r, Series& g, Series& b) {
  r.add(e.mae[0]);
  g.add(e.mae[1]);
  b.add(e.mae[2]);
}

void add_ssr_metrics(const ClusterReflectOptions& o, const ClusterSeries& s, Results& results) {
  auto& m = results.metrics;
  m["ssr_ms_avg"] = s.ssr_ms.avg();
  m["boxprobe_ms_avg"] = s.box_ms.avg();
  m["probe_build_ms_avg"] = s.probe_build_ms.avg();
  m["ssr_depth_passes_ms_avg"] = s.ssr_depth_ms.avg();
  m["ssr_trace_ms_avg"] = s.ssr_trace_ms.avg();
  m["ssr_fallback_pct_avg"] = s.ssr_fallback_pct.avg();
  m["ssr_fallback_pct_max"] = s.ssr_fallback_pct.max();
  m["ssr_fallback_rays_pct_avg"] = s.ssr_fallback_rays_pct.avg();
  for (int k = 0; k < 5; ++k) m[std::string("ssr_") + kSsrOutcomeNames[k] + "_rays_pct_avg"] = s.ssr_outcome_pct[k].avg();
  m["ssr_steps_per_ray_avg"] = s.ssr_steps.avg();
  m["ssr_confidence_avg"] = s.ssr_confidence.avg();
  if (!o.compare) return;
  m["ssr_mae_r"] = s.ssr_r.avg();
  m["ssr_mae_g"] = s.ssr_g.avg();
  m["ssr_mae_b"] = s.ssr_b.avg();
  m["boxprobe_mae_r"] = s.box_r.avg();
  m["boxprobe_mae_g"] = s.box_g.avg();
  m["boxprobe_mae_b"] = s.box_b.avg();
}

void add_metrics(const ClusterReflectOptions& o, const ClusterSeries& s, Results& results) {
  auto& m = results.metrics;
  m["frames"] = double(s.cluster_ms.values.size());
  m["frames_with_reflections"] = double(std::count_if(
      s.reflective_pct.values.begin(), s.reflective_pct.values.end(), [](double v) { return v > 0.0; }));
  m["reflective_pct_avg"] = s.reflective_pct.avg();
  m["reflective_pct_max"] = s.reflective_pct.max();
  m["clusters_avg"] = s.clusters.avg();
  m["clusters_max"] = s.clusters.max();
  m["samples_per_cluster_avg"] = s.samples_per_cluster.avg();
  m["cluster_ms_avg"] = s.cluster_ms.avg();
  m["cluster_ms_max"] = s.cluster_ms.max();
  m["gbuffer_clustering_ms_avg"] = s.step1_ms.avg();
  m["cluster_cameras_ms_avg"] = s.cameras_ms.avg();
  m["depth_images_ms_avg"] = s.images_ms.avg();
  m["intersection_ms_avg"] = s.intersection_ms.avg();
  m["texel_shading_ms_avg"] = s.texel_shading_ms.avg();
  m["cluster_cpu_ms_avg"] = s.cluster_cpu_ms.avg();
  m["gbuffer_clustering_cpu_ms_avg"] = s.step1_cpu_ms.avg();
  m["cluster_cameras_cpu_ms_avg"] = s.cameras_cpu_ms.avg();
  m["depth_images_cpu_ms_avg"] = s.images_cpu_ms.avg();
  m["intersection_cpu_ms_avg"] = s.intersection_cpu_ms.avg();
  m["triangles_drawn_avg"] = s.triangles_drawn.avg();
  m["shaded_texels_avg"] = s.shaded_texels.avg();
  m["env_fallback_pct_avg"] = s.fallback_pct.avg();
  m["texels_avg"] = s.texels.avg();
  m["second_layer_texels_avg"] = s.second_texels.avg();
  m["second_layer_rays_pct_avg"] = s.second_ray_pct.avg();
  m["own_layer_texels_avg"] = s.own_texels.avg();
  m["own_layer_rays_pct_avg"] = s.own_ray_pct.avg();
  m["own_exact_cpu_ms_avg"] = s.own_exact_cpu_ms.avg();
  m["behind_fill_pct_avg"] = s.fill_pct.avg();
  m["planar_samples_pct_avg"] = s.planar_pct.avg();
  m["planar_samples_pct_max"] = s.planar_pct.max();
  if (o.ssr) add_ssr_metrics(o, s, results);
  if (!o.compare) return;
  m["cluster_mae_r"] = s.mae_r.avg();
  m["cluster_mae_g"] = s.mae_g.avg();
  m["cluster_mae_b"] = s.mae_b.avg();
  m["envmap_mae_r"] = s.env_r.avg();
  m["envmap_mae_g"] = s.env_g.avg();
  m["envmap_mae_b"] = s.env_b.avg();
  m["occlusion_error_pct_avg"] = s.occlusion_pct.avg();
  m["occlusion_error_pct_max"] = s.occlusion_pct.max();
  m["occlusion_error_rays_pct_avg"] = s.occlusion_ray_pct.avg();
  m["occlusion_error_mirror_pct_avg"] = s.occlusion_mirror_pct.avg();
  m["occlusion_error_mirror_pct_max"] = s.occlusion_mirror_pct.max();
  m["occlusion_error_glossy_pct_avg"] = s.occlusion_glossy_pct.avg();
  for (int c = 1; c < kOcclusionCauses; ++c) {
    m[std::string("occlusion_") + kCauseNames[c] + "_pct_avg"] = s.cause_pct[c].avg();
    m[std::string("occlusion_") + kCauseNames[c] + "_mirror_pct_avg"] = s.cause_mirror_pct[c].avg();
  }
  m["reference_ms_avg"] = s.reference_ms.avg();
  m["reference_dynamic_ms_avg"] = s.reference_dynamic_ms.avg();
  m["envmap_ms_avg"] = s.envmap_ms.avg();
  m["envmap_build_ms_avg"] = s.envmap_build_ms.avg();
  m["envmap_maps_avg"] = s.envmap_groups.avg();
  m["speedup_static"] = s.reference_ms.avg() / s.cluster_ms.avg();
  m["speedup_dynamic"] = s.reference_dynamic_ms.avg() / s.cluster_ms.avg();
  m["reference_cpu_ms_avg"] = s.reference_cpu_ms.avg();
  m["reference_dynamic_cpu_ms_avg"] = s.reference_dynamic_cpu_ms.avg();
  m["speedup_static_cpu"] = s.reference_cpu_ms.avg() / s.cluster_cpu_ms.avg();
  m["speedup_dynamic_cpu"] = s.reference_dynamic_cpu_ms.avg() / s.cluster_cpu_ms.avg();
  if (o.full_reference) {
    m["full_mae_r"] = s.full_r.avg();
    m["full_mae_g"] = s.full_g.avg();
    m["full_mae_b"] = s.full_b.avg();
    m["traced_vs_full_mae"] = s.traced_full.avg();
  }
}

// The tables of the thesis' §4.7 (Tables 13–21) and, with compare, the error tables.
void add_tables(const ClusterReflectOptions& o, const ClusterSeries& s, const std::string& where,
                Results& results) {
  const std::string size = std::to_string(o.width) + "x" + std::to_string(o.height) + ", " +
                           std::to_string(o.reflection.supersample) + "x" +
                           std::to_string(o.reflection.supersample) + " ss";
  auto& t = results.tables;
  t.push_back(
      {"Frame rate (thesis Table 13), " + where + ", " + size,
       {"reflective_pct_max", "reflective_pct_avg", "embree_fps_max", "embree_fps_min", "embree_fps_avg",
        "embree_dynamic_fps_avg", "cluster_fps_max", "cluster_fps_min", "cluster_fps_avg"},
       {{s.reflective_pct.max(), s.reflective_pct.avg(), fps(s.reference_ms.min()), fps(s.reference_ms.max()),
         fps(s.reference_ms.avg()), fps(s.reference_dynamic_ms.avg()), fps(s.cluster_ms.min()),
         fps(s.cluster_ms.max()), fps(s.cluster_ms.avg())}}});
  t.push_back({"Step times in ms (thesis Table 14), " + where,
               {"gbuffer_clustering_max", "gbuffer_clustering_avg", "cameras_max", "cameras_avg",
                "depth_images_max", "depth_images_avg", "intersection_max", "intersection_avg"},
               {{s.step1_ms.max(), s.step1_ms.avg(), s.cameras_ms.max(), s.cameras_ms.avg(),
                 s.images_ms.max(), s.images_ms.avg(), s.intersection_ms.max(), s.intersection_ms.avg()}}});
  // One row per run: runs at other bin counts, output sizes and image scales make Tables 15–17.
  t.push_back({"Parameters vs frame rate (thesis Tables 15–17), " + where,
               {"clusters_avg", "width", "height", "resolution_scale", "texels_avg", "cluster_fps_avg"},
               {{s.clusters.avg(), double(o.width), double(o.height), double(o.cluster.resolution_scale),
                 s.texels.avg(), fps(s.cluster_ms.avg())}}});
  t.push_back({"Clusters (thesis Table 19), " + where,
               {"clusters_avg", "clusters_max", "samples_per_cluster_avg"},
               {{s.clusters.avg(), s.clusters.max(), s.samples_per_cluster.avg()}}});
  t.push_back({"Glossy cost (thesis Table 20), " + where,
               {"gloss_rays", "intersection_ms_avg", "embree_fps_avg", "cluster_fps_avg"},
               {{double(o.reflection.glossy_rays), s.intersection_ms.avg(), fps(s.reference_ms.avg()),
                 fps(s.cluster_ms.avg())}}});
  t.push_back({"Samples in planar clusters, % of reflective samples (thesis Table 21), " + where,
               {"avg", "max"},
               {{s.planar_pct.avg(), s.planar_pct.max()}}});
}

void add_compare_tables(const ClusterReflectOptions& o, const ClusterSeries& s, const std::string& where,
                        Results& results) {
  auto& t = results.tables;
  if (o.full_reference)
    t.push_back({"Error vs render_reference (shadows, area-light jitter, 1 bounce), " + where,
                 {"cluster_mae_r", "cluster_mae_g", "cluster_mae_b", "same_rays_embree_mae_avg"},
                 {{s.full_r.avg(), s.full_g.avg(), s.full_b.avg(), s.traced_full.avg()}}});
  t.push_back({"Error vs Embree on the same rays (thesis §4.7.1), " + where,
               {"method", "mae_r", "mae_g", "mae_b", "mae_max_channel_max_frame", "ms_avg"},
               {{std::string("cluster"), s.mae_r.avg(), s.mae_g.avg(), s.mae_b.avg(),
                 std::max({s.mae_r.max(), s.mae_g.max(), s.mae_b.max()}), s.cluster_ms.avg()},
                {std::string("envmap (rectified)"), s.env_r.avg(), s.env_g.avg(), s.env_b.avg(),
                 std::max({s.env_r.max(), s.env_g.max(), s.env_b.max()}), s.envmap_ms.avg()},
                {std::string("embree (static BVH)"), 0.0, 0.0, 0.0, 0.0, s.reference_ms.avg()},
                {std::string("embree (BVH rebuilt)"), 0.0, 0.0, 0.0, 0.0, s.reference_dynamic_ms.avg()}}});
  Table causes{"Occlusion errors, % of reflective samples (all / mirror only), " + where,
               {"cause", "all_samples_pct_avg", "mirror_samples_pct_avg"},
               {{std::string("total"), s.occlusion_pct.avg(), s.occlusion_mirror_pct.avg()}}};
  for (int c = 1; c < kOcclusionCauses; ++c)
    causes.rows.push_back({std::string(kCauseNames[c]), s.cause_pct[c].avg(), s.cause_mirror_pct[c].avg()});
  t.push_back(std::move(causes));
  t.push_back(
      {"Fallbacks, % of reflective samples, " + where,
       {"occlusion_error_rays_pct_avg", "occlusion_error_glossy_pct_avg", "env_fallback_pct_avg",
        "behind_fill_pct_avg"},
       {{s.occlusion_ray_pct.avg(), s.occlusion_glossy_pct.avg(), s.fallback_pct.avg(), s.fill_pct.avg()}}});
}

// SSR beside the box probe alone, cluster, rectified env mapping and Embree on the same rays.
void add_ssr_table(const ClusterSeries& s, const std::string& where, Results& results) {
  auto row = [](const char* name, const Series& r, const Series& g, const Series& b, const Series& ms,
                double fallback) {
    return std::vector<std::variant<std::string, double>>{std::string(name), r.avg(), g.avg(), b.avg(), ms.avg(), fallback};
  };
  Table t{"SSR with box-probe fallback vs Embree on the same rays, " + where,
          {"method", "mae_r", "mae_g", "mae_b", "ms_avg", "fallback_samples_pct"},
          {row("ssr + box probe", s.ssr_r, s.ssr_g, s.ssr_b, s.ssr_ms, s.ssr_fallback_pct.avg()),
           row("box probe alone", s.box_r, s.box_g, s.box_b, s.box_ms, 100.0),
           row("cluster", s.mae_r, s.mae_g, s.mae_b, s.cluster_ms, s.fallback_pct.avg()),
           row("envmap (rectified)", s.env_r, s.env_g, s.env_b, s.envmap_ms, 100.0)}};
  t.rows.push_back({std::string("embree (static BVH)"), 0.0, 0.0, 0.0, s.reference_ms.avg(), 0.0});
  results.tables.push_back(std::move(t));
}

// With ssr, the frame's SSR and box-probe errors against Embree on the same rays.
void add_ssr_errors(const FrameRun& f, const ImageF& reference, const ImageU8& mask, ClusterSeries& s) {
  add_mae(compare_images(compose_reflections(f.frame, f.ssr.radiance), reference, &mask), s.ssr_r, s.ssr_g, s.ssr_b);
  add_mae(compare_images(compose_reflections(f.frame, f.box_radiance), reference, &mask), s.box_r, s.box_g, s.box_b);
}

// With ssr, its images (and with compare the box probe's and both heat maps).
void write_ssr_images(const FrameRun& f, const ImageF& reference, const ImageU8& mask, bool compare,
                      const StudyOutput& out, Results& results) {
  const ImageF ssr = compose_reflections(f.frame, f.ssr.radiance);
  write_image(out, results, "ssr", "ssr.png", ssr);
  write_image(out, results, "ssr_fallback", "ssr_fallback.png", ssr_fallback_image(f.frame, f.ssr, ssr));
  if (!compare) return;
  const ImageF box = compose_reflections(f.frame, f.box_radiance);
  write_image(out, results, "boxprobe", "boxprobe.png", box);
  write_image(out, results, "error_ssr", "error_ssr.png",
              error_heatmap(error_image(ssr, reference, &mask), kErrorHeatmapMax, &mask));
  write_image(out, results, "error_boxprobe", "error_boxprobe.png",
              error_heatmap(error_image(box, reference, &mask), kErrorHeatmapMax, &mask));
}

}  // namespace

void validate(const ClusterReflectOptions& o) {
  require_in_range(o.width, 1, kMaxImageSide, "--width");
  require_in_range(o.height, 1, kMaxImageSide, "--height");
  require_in_range(o.reflection.supersample, 1, 8, "--ss");
  require_in_range(o.reflection.glossy_rays, 1, 1024, "--gloss-rays", "for --method cluster");
  require_in_range(o.reflection.area_light_samples, 1, 64, "--light-samples");
  require_in_range(o.frames, 0, 100000, "--frames");
  require_at_least(o.frame_step, 1, "--frame-step");
  require_in_range(o.reps, 1, 100, "--reps");
  require_at_least(o.image_frame, -1, "--image-frame");
  if (o.full_reference && !o.compare) fail_input("--full-reference: needs --compare");
  const ClusteringOptions& c = o.cluster.clustering;
  require_in_range(c.max_theta_bins, 1, 1000, "--theta-bins");
  require_in_range(c.max_phi_bins, 1, 1000, "--phi-bins");
  require_in_range(c.min_bin_scale, 0.0f, 1.0f, "--min-bin-scale");
  require_above_at_most(o.cluster.resolution_scale, 0.0f, 8.0f, "--resolution-scale");
  require_in_range(o.cube_size, 1, kMaxImageSide, "--cube-size");
  validate(o.envmap_groups);
  require_in_range(o.cluster.march_block, 0, 256, "--march-block");
  require_in_range(o.cluster.lod_texels, 0.0f, 16.0f, "--lod");
  require_in_range(o.cluster.glossy_march_coarse, 1, 64, "--glossy-march-coarse");
  validate(o.ssr_options);
}

void validate(const ClusterReflectOptions& o, const Scene& scene) {
  const Schedule s = schedule(scene, o);
  if (!s.sequence) pick_camera(scene, o.camera, o.width, o.height);
  if (reflective_objects(scene).empty()) fail_input("--scene: '" + scene.name + "' has no reflective object");
}

namespace {

// Frames [first, last) of the schedule into `s`; the images, when the image frame (the first
// one rendered unless --image-frame) is among them, into `out` and `results`.
void run_frames(const Scene& rest, const ClusterReflectOptions& o, const Schedule& sched, int first, int last,
                const StudyOutput& out, ClusterSeries& s, Results& results, Progress* progress) {
  const float far = scene_far_plane(rest);
  const ReflectionOptions& ro = o.reflection;
  const int image_index = o.image_frame < 0 ? sched.indices.front() : o.image_frame;
  if (progress) progress->begin("reflect cluster", last - first);
  // The levels of detail, once per scene (rest pose; posing is rigid per object).
  SceneLod lod;
  ClusterReflectOptions with_lod = o;
  if (o.cluster.lod_texels > 0.0f) {
    lod = build_scene_lod(rest, lod_cells(std::max(scene_bounds(rest).diagonal(), 1e-3f), kClusterLodLevels));
    with_lod.cluster.lod = &lod;
  }
  for (int k = first; k < last; ++k) {
    const int frame_index = sched.indices[size_t(k)];
    if (progress) progress->step("frame " + std::to_string(frame_index) + "/" + std::to_string(sched.frames));
    const float t = sched.time_of(frame_index);
    const Scene posed = has_animation(rest) ? pose_scene(rest, t) : Scene{};
    const Scene& scene = has_animation(rest) ? posed : rest;
    const Camera camera = sched.sequence ? camera_at_time(*sched.path, t, o.width, o.height, 0.01f, far)
                                         : pick_camera(rest, o.camera, o.width, o.height);
    const FrameRun f = run_frame(scene, camera, with_lod, ro);
    const ImageU8 mask = reflective_pixel_mask(f.frame);
    size_t reflective = 0;
    for (uint8_t m : mask.data()) reflective += m;
    add_frame(f, reflective, mask.pixel_count(), o.compare, s);
    if (o.ssr) add_ssr_frame(f, s);  // its times over every frame, as the cluster method's
    const ImageF color = compose_reflections(f.frame, f.cluster.radiance);
    const ImageF reference = o.compare ? compose_reflections(f.frame, f.traced.radiance) : ImageF();
    const ImageF envmap = o.compare ? compose_reflections(f.frame, f.env_radiance) : ImageF();
    if (o.compare && reflective > 0) {
      add_occlusion_errors(f, std::max<double>(1.0, double(f.cluster.stats.reflective_samples)), s);
      add_mae(compare_images(color, reference, &mask), s.mae_r, s.mae_g, s.mae_b);
      add_mae(compare_images(envmap, reference, &mask), s.env_r, s.env_g, s.env_b);
      if (o.full_reference) add_full_reference_errors(scene, f, camera, ro, color, reference, mask, s);
      if (o.ssr) add_ssr_errors(f, reference, mask, s);
    }
    if (frame_index == image_index) {
      write_image(out, results, "cluster", "cluster.png", color);
      write_image(out, results, "clusters", "clusters.png", cluster_image(f.frame, f.cluster, color));
      if (o.compare) {
        write_image(out, results, "reference", "reference.png", reference);
        write_image(out, results, "envmap", "envmap.png", envmap);
        // Error heat maps over the reflective pixels.
        write_image(out, results, "error_cluster", "error_cluster.png",
                    error_heatmap(error_image(color, reference, &mask), kErrorHeatmapMax, &mask));
        write_image(out, results, "error_envmap", "error_envmap.png",
                    error_heatmap(error_image(envmap, reference, &mask), kErrorHeatmapMax, &mask));
      }
      if (o.ssr) write_ssr_images(f, reference, mask, o.compare, out, results);
    }
  }
  if (progress) progress->end();
}

// The run's metrics and tables from every frame's series.
void add_results(const Scene& rest, const ClusterReflectOptions& o, const Schedule& sched, const ClusterSeries& s,
                 Results& results) {
  add_metrics(o, s, results);
  const std::string where =
      rest.name + " / " +
      (sched.path ? sched.path->name + (sched.sequence ? "" : " frame " + std::to_string(sched.indices[0]))
                  : "camera");
  add_tables(o, s, where, results);
  if (o.compare) add_compare_tables(o, s, where, results);
  if (o.compare && o.ssr) add_ssr_table(s, where, results);
}

// Every series of ClusterSeries, in declaration order: a frame part's figures.
template <typename S, typename F>
void for_each_series(S& s, F&& f) {
  for (auto* x : {&s.reflective_pct, &s.cluster_ms, &s.reference_ms, &s.reference_dynamic_ms, &s.envmap_ms,
                  &s.envmap_build_ms, &s.step1_ms, &s.cameras_ms, &s.images_ms, &s.intersection_ms, &s.clusters,
                  &s.samples_per_cluster, &s.occlusion_pct, &s.fallback_pct, &s.planar_pct, &s.mae_r, &s.mae_g,
                  &s.mae_b, &s.env_r, &s.env_g, &s.env_b, &s.texels, &s.fill_pct, &s.occlusion_ray_pct,
                  &s.occlusion_mirror_pct, &s.occlusion_glossy_pct, &s.full_r, &s.full_g, &s.full_b,
                  &s.traced_full, &s.second_texels, &s.second_ray_pct, &s.cluster_cpu_ms, &s.reference_cpu_ms,
                  &s.reference_dynamic_cpu_ms, &s.step1_cpu_ms, &s.cameras_cpu_ms, &s.images_cpu_ms,
                  &s.intersection_cpu_ms, &s.texel_shading_ms, &s.triangles_drawn, &s.shaded_texels, &s.own_texels,
                  &s.own_ray_pct, &s.own_exact_cpu_ms})
    f(*x);
  for (auto& x : s.cause_pct) f(x);
  for (auto& x : s.cause_mirror_pct) f(x);
  for (auto* x : {&s.ssr_ms, &s.box_ms, &s.ssr_r, &s.ssr_g, &s.ssr_b, &s.box_r, &s.box_g, &s.box_b,
                  &s.ssr_fallback_pct, &s.ssr_fallback_rays_pct, &s.ssr_steps, &s.ssr_confidence})
    f(*x);
  for (auto& x : s.ssr_outcome_pct) f(x);
  for (auto* x : {&s.ssr_depth_ms, &s.ssr_trace_ms, &s.envmap_groups, &s.probe_build_ms}) f(*x);
}

// A series added to ClusterSeries but not listed above would be lost by a split run.
constexpr size_t kClusterSeries = 45 + 2 * kOcclusionCauses + 12 + 5 + 4;
static_assert(sizeof(ClusterSeries) == kClusterSeries * sizeof(Series), "list every series in for_each_series");

}  // namespace

Results run_cluster_reflect(const Scene& rest, const ClusterReflectOptions& o, const StudyOutput& out,
                            Progress* progress) {
  validate(o);
  validate(o, rest);
  const Schedule sched = schedule(rest, o);
  ClusterSeries s;
  Results results;
  run_frames(rest, o, sched, 0, int(sched.indices.size()), out, s, results, progress);
  add_results(rest, o, sched, s, results);
  return results;
}

Results run_cluster_reflect_part(const Scene& rest, const ClusterReflectOptions& o, const FramePart& part,
                                 const StudyOutput& out, FrameFigures& figures, Progress* progress) {
  validate(o);
  validate(o, rest);
  const Schedule sched = schedule(rest, o);
  const auto [first, last] = frame_span(part, int(sched.indices.size()));
  ClusterSeries s;
  Results results;
  run_frames(rest, o, sched, first, last, out, s, results, progress);
  figures.series.clear();
  std::set<const Series*> listed;
  for_each_series(s, [&](const Series& x) {
    figures.series.push_back(x.values);
    listed.insert(&x);
  });
  if (listed.size() != kClusterSeries) throw std::logic_error("cluster_reflect: for_each_series lists a series twice");
  return results;
}

Results cluster_reflect_results(const Scene& rest, const ClusterReflectOptions& o, const FrameFigures& figures) {
  validate(o);
  validate(o, rest);
  if (figures.series.size() != kClusterSeries)
    throw std::runtime_error("cluster_reflect: " + std::to_string(figures.series.size()) + " series of frame figures, " +
                             std::to_string(kClusterSeries) + " expected");
  ClusterSeries s;
  size_t i = 0;
  for_each_series(s, [&](Series& x) { x.values = figures.series[i++]; });
  Results results;
  add_results(rest, o, schedule(rest, o), s, results);
  return results;
}

}  // namespace proxima::study
