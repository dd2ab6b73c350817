// `proxima reflect --method cluster`: reflections from screen-space clustered depth images
// (issue 7, thesis ch. 4) on one camera or along a camera path, optionally compared with
// Embree tracing the same rays and with rectified environment mapping on the same rays.
#include "cmd_reflect_cluster.h"
#include "frame_series.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/envmap_frame_reflections.h"
#include "proxima/reflect/envmap_lookup.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/scene/load.h"
#include "proxima/scene/shading.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::cli {

namespace {


// Output-resolution image of the samples: clusters in hashed colors, flagged samples red
// (environment fallback) and yellow (occlusion error), over a dimmed `color`.
ImageF cluster_image(const ReflectionFrame& frame, const ClusterReflections& cr, const ImageF& color) {
  ImageF out = color;
  for (float& v : out.data()) v *= 0.3f;
  const int sw = frame.sample_camera.width, k = frame.supersample;
  const float share = 1.0f / float(k * k);
  for (size_t i = 0; i < frame.sample_count(); ++i) {
    uint64_t h = mix64(cr.cluster[i]);
    vec3 c(float(h & 255) / 255.0f, float((h >> 8) & 255) / 255.0f, float((h >> 16) & 255) / 255.0f);
    if (cr.flags[i] & kEnvFallback) c = vec3(1, 0, 0);
    if (cr.flags[i] & kOcclusionError) c = vec3(1, 1, 0);
    const int x = int(frame.pixel[i] % uint32_t(sw)) / k, y = int(frame.pixel[i] / uint32_t(sw)) / k;
    for (int ch = 0; ch < 3; ++ch) out.at(x, y, ch) += share * (c[ch] - 0.3f * color.at(x, y, ch));
  }
  return out;
}

void validate(const ClusterReflectFlags& f) {
  const auto& c = f.common;
  if (c.width < 1 || c.width > 4096) fail_input("--width: must be in 1..4096");
  if (c.height < 1 || c.height > 4096) fail_input("--height: must be in 1..4096");
  if (c.threads < 0) fail_input("--threads: must be ≥ 0");
  if (f.reflection.supersample < 1 || f.reflection.supersample > 8) fail_input("--ss: must be in 1..8");
  if (f.reflection.glossy_rays < 1 || f.reflection.glossy_rays > 1024)
    fail_input("--gloss-rays: must be in 1..1024 for --method cluster");
  if (f.reflection.area_light_samples < 1 || f.reflection.area_light_samples > 64)
    fail_input("--light-samples: must be in 1..64");
  if (f.frames < 0 || f.frames > 100000) fail_input("--frames: must be in 0..100000");
  if (f.frame_step < 1) fail_input("--frame-step: must be ≥ 1");
  if (f.reps < 1 || f.reps > 100) fail_input("--reps: must be in 1..100");
  if (f.image_frame < -1) fail_input("--image-frame: must be ≥ -1");
  if (f.full_reference && !f.compare) fail_input("--full-reference: needs --compare");
  if (f.cluster.clustering.max_theta_bins < 1 || f.cluster.clustering.max_theta_bins > 1000)
    fail_input("--theta-bins: must be in 1..1000");
  if (f.cluster.clustering.max_phi_bins < 1 || f.cluster.clustering.max_phi_bins > 1000)
    fail_input("--phi-bins: must be in 1..1000");
  if (!(f.cluster.clustering.min_bin_scale >= 0.0f && f.cluster.clustering.min_bin_scale <= 1.0f))
    fail_input("--min-bin-scale: must be in [0, 1]");
  if (!(f.cluster.resolution_scale > 0.0f && f.cluster.resolution_scale <= 8.0f))
    fail_input("--resolution-scale: must be in (0, 8]");
  if (f.cube_size < 1 || f.cube_size > 4096) fail_input("--cube-size: must be in 1..4096");
  if (f.cluster.march_block < 0 || f.cluster.march_block > 256) fail_input("--march-block: must be in 0..256");
}

const char* const kCauseNames[kOcclusionCauses] = {"none", "behind_near_plane", "outside_image",
                                                   "own_curved_reflector", "hidden_in_image"};

}  // namespace

void add_cluster_reflect_flags(CLI::App* app, ClusterReflectFlags& f) {
  const auto group = "cluster (--method cluster)";
  app->add_option("--frames", f.frames,
                  "cluster, temporal: with --path and no --frame, the path is divided into N frames (0 = its own count)")
      ->capture_default_str()
      ->group(group);
  app->add_option("--frame-step", f.frame_step, "cluster, temporal: render every N-th of those frames")
      ->capture_default_str()
      ->group(group);
  app->add_option("--ss", f.reflection.supersample, "cluster: K×K samples per pixel (the reference's sub-pixel grid)")
      ->capture_default_str()
      ->group(group);
  app->add_option("--theta-bins", f.cluster.clustering.max_theta_bins, "cluster: MAXTHETABINS")
      ->capture_default_str()
      ->group(group);
  app->add_option("--phi-bins", f.cluster.clustering.max_phi_bins, "cluster: MAXPHIBINS")
      ->capture_default_str()
      ->group(group);
  app->add_option("--min-bin-scale", f.cluster.clustering.min_bin_scale,
                  "cluster: lower bound of a reflector's bin scale per axis (0..1; 1 = 13×8 bins for every reflector)")
      ->capture_default_str()
      ->group(group);
  app->add_option("--resolution-scale", f.cluster.resolution_scale, "cluster: image texels per pixel footprint")
      ->capture_default_str()
      ->group(group);
  app->add_option("--second-layer", f.cluster.second_layer,
                  "cluster: glossy and curved clusters get a second depth layer that rays hidden behind a nearer "
                  "surface are marched in (true/false)")
      ->capture_default_str()
      ->group(group);
  app->add_option("--march-block", f.cluster.march_block,
                  "cluster: block size of the depth minima the march skips with (0 = texel by texel; same result)")
      ->capture_default_str()
      ->group(group);
  app->add_option("--image-frame", f.image_frame, "cluster, temporal: frame whose images are written (-1 = cluster: the first rendered; temporal: the first that reuses a key frame)")
      ->capture_default_str()
      ->group(group);
  app->add_flag("--full-reference", f.full_reference,
                "cluster: with --compare, also render_reference (shadows, jittered area-light samples, 1 bounce); "
                "untimed")
      ->group(group);
}

int run_cluster_reflect(const ClusterReflectFlags& f) {
  validate(f);
  ThreadLimit limit(f.common.threads);
  const Scene rest = load_scene(f.common.scene);
  // Frames: one (the scene camera --camera, or --path with --frame), or the path divided
  // into --frames frames, every --frame-step-th rendered.
  const CameraPath* path = nullptr;
  int frames = 1;
  if (!f.camera.path.empty()) {
    const int path_index = find_camera_path(rest, f.camera.path);
    if (path_index < 0)
      fail_input("--path: scene '" + rest.name + "' has no camera path '" + f.camera.path + "' (" +
                 std::to_string(rest.camera_paths.size()) + " paths)");
    path = &rest.camera_paths[size_t(path_index)];
    frames = f.frames > 0 ? f.frames : path->frames;
  }
  const bool sequence = path && !f.frame_given;
  std::vector<int> indices;
  if (sequence) {
    for (int i = 0; i < frames; i += f.frame_step) indices.push_back(i);
  } else {
    indices.push_back(f.frame_given ? f.camera.frame : 0);
    pick_camera(rest, f.camera, f.common.width, f.common.height);  // InputError before --out is made
  }
  if (reflective_objects(rest).empty()) fail_input("--scene: '" + rest.name + "' has no reflective object");
  const auto out = prepare_out_dir(f.common.out);
  const float far = scene_far_plane(rest);
  ReflectionOptions ro = f.reflection;
  ro.seed = f.common.seed;
  auto time_of = [&](int index) {
    if (!path) return 0.0f;
    if (!sequence) return frame_time(*path, index);
    const float t0 = path->keys.front().time, t1 = path->keys.back().time;
    return frames > 1 ? t0 + float(index) * (t1 - t0) / float(frames - 1) : t0;
  };

  Series reflective_pct, cluster_ms, reference_ms, reference_dynamic_ms, envmap_ms, envmap_build_ms, step1_ms,
      cameras_ms, images_ms, intersection_ms, clusters, samples_per_cluster, occlusion_pct, fallback_pct, planar_pct,
      mae_r, mae_g, mae_b, env_r, env_g, env_b, texels, fill_pct, occlusion_ray_pct, occlusion_mirror_pct,
      occlusion_glossy_pct, full_r, full_g, full_b, traced_full, second_texels, second_ray_pct;
  Series cause_pct[kOcclusionCauses], cause_mirror_pct[kOcclusionCauses];
  Results results;
  results.command = command_line();
  results.threads = active_threads();
  bool wrote_images = false;
  for (const int frame_index : indices) {
    const float t = time_of(frame_index);
    const Scene posed = has_animation(rest) ? pose_scene(rest, t) : Scene{};
    const Scene& scene = has_animation(rest) ? posed : rest;
    const Camera camera = sequence ? camera_at_time(*path, t, f.common.width, f.common.height, 0.01f, far)
                                   : pick_camera(rest, f.camera, f.common.width, f.common.height);

    // Side by side, `reps` times; medians per frame.
    std::vector<double> c_ms, r_ms, b_ms, e_ms, s1, s2, s3, s4;
    ReflectionFrame frame;
    ClusterReflections cluster;
    TracedReflections traced;
    std::unique_ptr<RayScene> rays;
    DistanceCubeMap map;
    std::vector<vec3> env_radiance;
    const std::vector<uint32_t> reflectors = reflective_objects(scene);
    RectifyOptions rectify;
    rectify.D = f.distance > 0.0f ? f.distance : scene_bounds(scene).diagonal();
    rectify.d_e = f.d_e;
    rectify.edge = f.edge_fallback ? EdgeRule::PlainFallback : EdgeRule::Black;
    for (int rep = 0; rep < f.reps; ++rep) {
      Stopwatch watch;
      const std::vector<Bounds3> bounds = raster_object_bounds(scene);
      frame = prepare_reflection_frame(scene, camera, ro, bounds);
      const double step1 = watch.elapsed_ms();
      if (f.compare) {
        rays = std::make_unique<RayScene>(scene);
        b_ms.push_back(rays->build_ms());
        traced = trace_reflections(scene, *rays, frame);
        r_ms.push_back(step1 + traced.ms);
        if (rep == 0) {
          // The env map of the reflectors' environment from their common centre, texels
          // shaded as the cluster images' (unshadowed); built once per frame (the scene moves).
          DistanceCubeMapOptions mo;
          mo.resolution = f.cube_size;
          mo.area_light_samples = ro.area_light_samples;
          mo.seed = ro.seed;
          mo.exclude = reflectors;
          mo.shade = [&](uint32_t tri, float u, float v, vec3 toward) {
            return shade_reflected_point(scene, tri, u, v, toward, ro.area_light_samples);
          };
          Stopwatch w;
          map = render_distance_cube_map(scene, *rays, projection_center(scene, reflectors), mo);
          envmap_build_ms.add(w.elapsed_ms());
        }
        Stopwatch w;
        env_radiance = envmap_frame_reflections(scene, frame, map, EnvmapMethod::Rectified, rectify);
        e_ms.push_back(step1 + w.elapsed_ms());
      }
      cluster = render_cluster_reflections(scene, frame, f.cluster, bounds, f.compare ? &traced : nullptr);
      const ClusterFrameStats& st = cluster.stats;
      s1.push_back(step1 + st.clustering_ms);
      s2.push_back(st.cameras_ms);
      s3.push_back(st.depth_images_ms);
      s4.push_back(st.intersection_ms);
      c_ms.push_back(s1.back() + s2.back() + s3.back() + s4.back());
    }
    const ClusterFrameStats& st = cluster.stats;
    const ImageU8 mask = reflective_pixel_mask(frame);
    size_t reflective = 0;
    for (uint8_t m : mask.data()) reflective += m;
    const double samples = std::max<double>(1.0, double(st.reflective_samples));
    reflective_pct.add(100.0 * double(reflective) / double(mask.pixel_count()));
    cluster_ms.add(median(c_ms));
    step1_ms.add(median(s1));
    cameras_ms.add(median(s2));
    images_ms.add(median(s3));
    intersection_ms.add(median(s4));
    if (reflective > 0) {  // cluster figures over the frames that show reflective pixels
      clusters.add(double(st.clusters));
      texels.add(double(st.texels));
      second_texels.add(double(st.second_layer_texels));
      second_ray_pct.add(100.0 * double(st.second_layer_rays) / std::max<double>(1.0, double(st.rays)));
      samples_per_cluster.add(double(st.reflective_samples) / double(st.clusters));
      planar_pct.add(100.0 * double(st.planar_samples) / samples);
    }
    fallback_pct.add(100.0 * double(st.env_fallback_samples) / samples);
    fill_pct.add(100.0 * double(st.behind_fill_samples) / samples);
    const ImageF color = compose_reflections(frame, cluster.radiance);
    const ImageF reference = f.compare ? compose_reflections(frame, traced.radiance) : ImageF();
    const ImageF envmap = f.compare ? compose_reflections(frame, env_radiance) : ImageF();
    if (f.compare) {
      reference_ms.add(median(r_ms));
      reference_dynamic_ms.add(median(r_ms) + median(b_ms));
      envmap_ms.add(median(e_ms));
    }
    // Error figures average over the frames that show reflective pixels.
    if (f.compare && reflective > 0) {
      occlusion_pct.add(100.0 * double(st.occlusion_error_samples) / samples);
      occlusion_ray_pct.add(100.0 * double(st.occlusion_error_rays) / std::max<double>(1.0, double(st.rays)));
      // Causes, over all reflective samples and over the mirror samples (one ray each).
      uint64_t mirror_cause[kOcclusionCauses] = {}, glossy_errors = 0;
      for (size_t i = 0; i < frame.sample_count(); ++i) {
        const bool mirror = glossy_lobe_half_angle(frame.gloss[i]) <= 0.0f;
        if (mirror) ++mirror_cause[cluster.occlusion_cause[i]];
        else glossy_errors += cluster.occlusion_cause[i] != uint8_t(OcclusionCause::None);
      }
      for (int c = 1; c < kOcclusionCauses; ++c) {
        cause_pct[c].add(100.0 * double(st.occlusion_cause_samples[c]) / samples);
        if (st.mirror_samples > 0) cause_mirror_pct[c].add(100.0 * double(mirror_cause[c]) / double(st.mirror_samples));
      }
      if (st.mirror_samples > 0)
        occlusion_mirror_pct.add(100.0 * double(st.mirror_occlusion_error_samples) / double(st.mirror_samples));
      if (st.mirror_samples < st.reflective_samples)
        occlusion_glossy_pct.add(100.0 * double(glossy_errors) / double(st.reflective_samples - st.mirror_samples));
      const ImageError err = compare_images(color, reference, &mask);
      mae_r.add(err.mae[0]);
      mae_g.add(err.mae[1]);
      mae_b.add(err.mae[2]);
      const ImageError env_err = compare_images(envmap, reference, &mask);
      env_r.add(env_err.mae[0]);
      env_g.add(env_err.mae[1]);
      env_b.add(env_err.mae[2]);
      if (f.full_reference) {
        // Ground truth with shadows and jittered area-light samples; the Embree pass on the
        // same rays against it isolates what the shared unshadowed shading costs.
        ReferenceOptions full_opts;
        full_opts.supersample = ro.supersample;
        full_opts.area_light_samples = ro.area_light_samples;
        full_opts.glossy_rays = ro.glossy_rays;
        full_opts.max_bounces = 1;
        full_opts.seed = ro.seed;
        const ImageF full = render_reference(scene, *rays, camera, full_opts);
        const ImageError cluster_err = compare_images(color, full, &mask);
        full_r.add(cluster_err.mae[0]);
        full_g.add(cluster_err.mae[1]);
        full_b.add(cluster_err.mae[2]);
        traced_full.add(compare_images(reference, full, &mask).mae_avg);
      }
    }
    std::fprintf(stderr, "frame %d/%d: %llu clusters, %llu texels, cluster %.0f ms%s\n", frame_index, frames,
                 static_cast<unsigned long long>(st.clusters), static_cast<unsigned long long>(st.texels),
                 cluster_ms.values.back(),
                 f.compare ? (", embree " + std::to_string(int(reference_ms.values.back())) + " ms").c_str() : "");
    if (!wrote_images && (f.image_frame < 0 || f.image_frame == frame_index)) {
      write_png_linear(out / "cluster.png", color);
      write_png_linear(out / "clusters.png", cluster_image(frame, cluster, color));
      results.images["cluster"] = "cluster.png";
      results.images["clusters"] = "clusters.png";
      if (f.compare) {
        write_png_linear(out / "reference.png", reference);
        write_png_linear(out / "envmap.png", envmap);
        // Error heat maps over the reflective pixels, 0–20 on the 0–255 scale.
        write_png_linear(out / "error_cluster.png", error_heatmap(error_image(color, reference, &mask), 20.0f, &mask));
        write_png_linear(out / "error_envmap.png", error_heatmap(error_image(envmap, reference, &mask), 20.0f, &mask));
        results.images["reference"] = "reference.png";
        results.images["envmap"] = "envmap.png";
        results.images["error_cluster_0_20"] = "error_cluster.png";
        results.images["error_envmap_0_20"] = "error_envmap.png";
      }
      wrote_images = true;
    }
  }

  auto& m = results.metrics;
  m["frames"] = double(cluster_ms.values.size());
  m["frames_with_reflections"] = double(std::count_if(reflective_pct.values.begin(), reflective_pct.values.end(),
                                                      [](double v) { return v > 0.0; }));
  m["reflective_pct_avg"] = reflective_pct.avg();
  m["reflective_pct_max"] = reflective_pct.max();
  m["clusters_avg"] = clusters.avg();
  m["clusters_max"] = clusters.max();
  m["samples_per_cluster_avg"] = samples_per_cluster.avg();
  m["cluster_ms_avg"] = cluster_ms.avg();
  m["cluster_ms_max"] = cluster_ms.max();
  m["gbuffer_clustering_ms_avg"] = step1_ms.avg();
  m["cluster_cameras_ms_avg"] = cameras_ms.avg();
  m["depth_images_ms_avg"] = images_ms.avg();
  m["intersection_ms_avg"] = intersection_ms.avg();
  m["env_fallback_pct_avg"] = fallback_pct.avg();
  m["texels_avg"] = texels.avg();
  m["second_layer_texels_avg"] = second_texels.avg();
  m["second_layer_rays_pct_avg"] = second_ray_pct.avg();
  m["behind_fill_pct_avg"] = fill_pct.avg();
  m["planar_samples_pct_avg"] = planar_pct.avg();
  m["planar_samples_pct_max"] = planar_pct.max();
  const std::string where =
      rest.name + " / " + (path ? path->name + (sequence ? "" : " frame " + std::to_string(indices[0])) : "camera");
  const std::string size = std::to_string(f.common.width) + "x" + std::to_string(f.common.height) + ", " +
                           std::to_string(ro.supersample) + "x" + std::to_string(ro.supersample) + " ss";
  results.tables.push_back({"Frame rate (thesis Table 13), " + where + ", " + size,
                            {"reflective_pct_max", "reflective_pct_avg", "embree_fps_max", "embree_fps_min",
                             "embree_fps_avg", "embree_dynamic_fps_avg", "cluster_fps_max", "cluster_fps_min",
                             "cluster_fps_avg"},
                            {{reflective_pct.max(), reflective_pct.avg(), fps(reference_ms.min()),
                              fps(reference_ms.max()), fps(reference_ms.avg()), fps(reference_dynamic_ms.avg()),
                              fps(cluster_ms.min()), fps(cluster_ms.max()), fps(cluster_ms.avg())}}});
  results.tables.push_back({"Step times in ms (thesis Table 14), " + where,
                            {"gbuffer_clustering_max", "gbuffer_clustering_avg", "cameras_max", "cameras_avg",
                             "depth_images_max", "depth_images_avg", "intersection_max", "intersection_avg"},
                            {{step1_ms.max(), step1_ms.avg(), cameras_ms.max(), cameras_ms.avg(), images_ms.max(),
                              images_ms.avg(), intersection_ms.max(), intersection_ms.avg()}}});
  // One row per run: runs at other bin counts, output sizes and image scales make Tables 15–17.
  results.tables.push_back({"Parameters vs frame rate (thesis Tables 15–17), " + where,
                            {"clusters_avg", "width", "height", "resolution_scale", "texels_avg", "cluster_fps_avg"},
                            {{clusters.avg(), double(f.common.width), double(f.common.height),
                              double(f.cluster.resolution_scale), texels.avg(), fps(cluster_ms.avg())}}});
  results.tables.push_back({"Clusters (thesis Table 19), " + where,
                            {"clusters_avg", "clusters_max", "samples_per_cluster_avg"},
                            {{clusters.avg(), clusters.max(), samples_per_cluster.avg()}}});
  results.tables.push_back({"Glossy cost (thesis Table 20), " + where,
                            {"gloss_rays", "intersection_ms_avg", "embree_fps_avg", "cluster_fps_avg"},
                            {{double(ro.glossy_rays), intersection_ms.avg(), fps(reference_ms.avg()),
                              fps(cluster_ms.avg())}}});
  results.tables.push_back({"Samples in planar clusters, % of reflective samples (thesis Table 21), " + where,
                            {"avg", "max"},
                            {{planar_pct.avg(), planar_pct.max()}}});
  if (f.compare) {
    m["cluster_mae_r"] = mae_r.avg();
    m["cluster_mae_g"] = mae_g.avg();
    m["cluster_mae_b"] = mae_b.avg();
    m["envmap_mae_r"] = env_r.avg();
    m["envmap_mae_g"] = env_g.avg();
    m["envmap_mae_b"] = env_b.avg();
    m["occlusion_error_pct_avg"] = occlusion_pct.avg();
    m["occlusion_error_pct_max"] = occlusion_pct.max();
    m["occlusion_error_rays_pct_avg"] = occlusion_ray_pct.avg();
    m["occlusion_error_mirror_pct_avg"] = occlusion_mirror_pct.avg();
    m["occlusion_error_mirror_pct_max"] = occlusion_mirror_pct.max();
    m["occlusion_error_glossy_pct_avg"] = occlusion_glossy_pct.avg();
    for (int c = 1; c < kOcclusionCauses; ++c) {
      m[std::string("occlusion_") + kCauseNames[c] + "_pct_avg"] = cause_pct[c].avg();
      m[std::string("occlusion_") + kCauseNames[c] + "_mirror_pct_avg"] = cause_mirror_pct[c].avg();
    }
    m["reference_ms_avg"] = reference_ms.avg();
    m["reference_dynamic_ms_avg"] = reference_dynamic_ms.avg();
    m["envmap_ms_avg"] = envmap_ms.avg();
    m["envmap_build_ms_avg"] = envmap_build_ms.avg();
    m["speedup_static"] = reference_ms.avg() / cluster_ms.avg();
    m["speedup_dynamic"] = reference_dynamic_ms.avg() / cluster_ms.avg();
    if (f.full_reference) {
      m["full_mae_r"] = full_r.avg();
      m["full_mae_g"] = full_g.avg();
      m["full_mae_b"] = full_b.avg();
      m["traced_vs_full_mae"] = traced_full.avg();
      results.tables.push_back({"Error vs render_reference (shadows, area-light jitter, 1 bounce), " + where,
                                {"cluster_mae_r", "cluster_mae_g", "cluster_mae_b", "same_rays_embree_mae_avg"},
                                {{full_r.avg(), full_g.avg(), full_b.avg(), traced_full.avg()}}});
    }
    results.tables.push_back({"Error vs Embree on the same rays (thesis §4.7.1), " + where,
                              {"method", "mae_r", "mae_g", "mae_b", "mae_max_channel_max_frame", "ms_avg"},
                              {{std::string("cluster"), mae_r.avg(), mae_g.avg(), mae_b.avg(),
                                std::max({mae_r.max(), mae_g.max(), mae_b.max()}), cluster_ms.avg()},
                               {std::string("envmap (rectified)"), env_r.avg(), env_g.avg(), env_b.avg(),
                                std::max({env_r.max(), env_g.max(), env_b.max()}), envmap_ms.avg()},
                               {std::string("embree (static BVH)"), 0.0, 0.0, 0.0, 0.0, reference_ms.avg()},
                               {std::string("embree (BVH rebuilt)"), 0.0, 0.0, 0.0, 0.0, reference_dynamic_ms.avg()}}});
    Table causes{"Occlusion errors, % of reflective samples (all / mirror only), " + where,
                 {"cause", "all_samples_pct_avg", "mirror_samples_pct_avg"},
                 {{std::string("total"), occlusion_pct.avg(), occlusion_mirror_pct.avg()}}};
    for (int c = 1; c < kOcclusionCauses; ++c)
      causes.rows.push_back({std::string(kCauseNames[c]), cause_pct[c].avg(), cause_mirror_pct[c].avg()});
    results.tables.push_back(std::move(causes));
    results.tables.push_back({"Fallbacks, % of reflective samples, " + where,
                              {"occlusion_error_rays_pct_avg", "occlusion_error_glossy_pct_avg", "env_fallback_pct_avg",
                               "behind_fill_pct_avg"},
                              {{occlusion_ray_pct.avg(), occlusion_glossy_pct.avg(), fallback_pct.avg(),
                                fill_pct.avg()}}});
  }
  publish_results(out, results);
  return 0;
}

}  // namespace proxima::cli
