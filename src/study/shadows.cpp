// The soft-shadow study (thesis ch. 3: Algorithm 4 reconstructs the depth images, Algorithm
// 5 renders soft shadows from the reconstruction; errors of §3.4.2; docs/shadows.md). One
// light, one set of receivers and one ground truth shared by every sampling.
#include "proxima/study/shadows.h"

#include <cstdio>
#include <string>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/error.h"
#include "proxima/core/range_check.h"
#include "proxima/shadows/light_setup.h"
#include "proxima/shadows/light_visibility.h"
#include "proxima/shadows/shadow_error.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::study {

namespace {

std::string pair_text(double mean, double max) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f/%.0f", mean, max);
  return buf;
}

void check_side(int side, const char* flag) {
  require_in_range(side, 8, kMaxImageSide, flag);
}

struct Tables {
  Table errors, rays, times;
};

Tables make_tables(const Scene& scene, const ShadowsOptions& o) {
  const std::string setting = scene.name + ", light " + std::to_string(o.light_size).substr(0, 5) + " x diag, " +
                              std::to_string(o.light_samples) + "x" + std::to_string(o.light_samples) +
                              " samples, ref " + std::to_string(o.ref_res) + ", out " + std::to_string(o.out_res) +
                              ", shadow maps " + std::to_string(o.shadow_res);
  return {{"Soft-shadow error vs shadow maps of the geometry, mean/max (thesis Table 8): " + setting,
           {"sampling", "intensity error", "visibility error"}, {}},
          {"Soft-shadow error vs Embree shadow rays, mean/max: " + setting,
           {"sampling", "intensity error", "visibility error"}, {}},
          {"Time per step, ms (thesis Table 11): " + setting,
           {"sampling", "1: reference images", "2: reconstruction", "3: soft shadows", "occluder triangles"}, {}}};
}

// The ground truths: their images, their time, and how far shadow maps are from rays.
void add_ground_truth(Results& results, Tables& t, const Scene& scene, const ShadowSetting& s, bool rays,
                      const StudyOutput& out) {
  t.times.rows.push_back({"geometry (ground truth)", 0.0, 0.0, s.truth_ms, double(scene.triangles.size())});
  if (rays) {
    const ShadowError g = compare_visibility(s.truth, s.exact, s.receivers);
    t.rays.rows.push_back({"geometry shadow maps", pair_text(g.intensity_mean, g.intensity_max),
                           pair_text(g.visibility_mean, g.visibility_max)});
    results.metrics["geometry_vs_rays_intensity_error_mean"] = g.intensity_mean;
    results.metrics["geometry_vs_rays_visibility_error_mean"] = g.visibility_mean;
    results.metrics["time_rays_ms"] = s.rays_ms;
  }
  write_image(out, results, "geometry_shadow", "geometry_shadow.png", shadow_image(s.truth, s.receivers));
  if (rays) write_image(out, results, "rays_shadow", "rays_shadow.png", shadow_image(s.exact, s.receivers));
}

void add_errors(Results& results, const std::string& p, const char* suffix, const ShadowError& e) {
  results.metrics[p + "intensity_error" + suffix + "mean"] = e.intensity_mean;
  results.metrics[p + "intensity_error" + suffix + "max"] = e.intensity_max;
  results.metrics[p + "visibility_error" + suffix + "mean"] = e.visibility_mean;
  results.metrics[p + "visibility_error" + suffix + "max"] = e.visibility_max;
}

// One sampling: steps 1–3, its errors against both ground truths, its images.
void add_sampling(Results& results, Tables& t, const Scene& scene, const RayScene& rays, const ShadowSetting& s,
                  const ShadowsOptions& o, ShadowSampling sampling, const StudyOutput& out) {
  const std::string name = shadow_sampling_name(sampling);
  const std::string p = o.samplings.size() > 1 ? name + "_" : "";
  const ShadowSamplingRun run = run_shadow_sampling(scene, rays, s, o, sampling);
  const Occluders& occluders = run.occluders;
  const ShadowMapStats& st = run.stats;
  const double shadow_ms = st.ms;
  const LightVisibility& v = run.visibility;
  const ShadowError e = compare_visibility(v, s.truth, s.receivers);
  add_errors(results, p, "_", e);
  const double triangles = double(occluders.scene.triangles.size());
  results.metrics[p + "time_reference_ms"] = occluders.reference_ms;
  results.metrics[p + "time_reconstruct_ms"] = occluders.reconstruct_ms;
  results.metrics[p + "time_shadow_ms"] = shadow_ms;
  results.metrics[p + "time_shadow_raster_ms"] = st.raster_ms;
  results.metrics[p + "shadow_texels"] = double(st.texels);
  results.metrics[p + "shadow_triangles_drawn"] = double(st.triangles_drawn);
  results.metrics[p + "occluder_triangles"] = triangles;
  results.metrics[p + "reference_samples"] = double(occluders.samples);
  t.errors.rows.push_back(
      {name, pair_text(e.intensity_mean, e.intensity_max), pair_text(e.visibility_mean, e.visibility_max)});
  t.times.rows.push_back({name, occluders.reference_ms, occluders.reconstruct_ms, shadow_ms, triangles});
  if (!o.no_rays) {
    const ShadowError r = compare_visibility(v, s.exact, s.receivers);
    add_errors(results, p, "_rays_", r);
    t.rays.rows.push_back(
        {name, pair_text(r.intensity_mean, r.intensity_max), pair_text(r.visibility_mean, r.visibility_max)});
  }
  write_image(out, results, name + "_shadow", name + "_shadow.png", shadow_image(v, s.receivers));
  write_image(out, results, name + "_error", name + "_error.png", e.image);
}

}  // namespace

ShadowSetting shadow_setting(const Scene& scene, const RayScene& rays, const Camera& view, const ShadowsOptions& o) {
  ShadowSetting s;
  s.light = shadow_light(scene, o.light_size);
  s.samples = light_samples(s.light, o.light_samples);
  s.receivers = render_receivers(scene, view);
  std::vector<vec3> eyes = s.samples.points;
  for (const vec3& c : light_corners(s.light)) eyes.push_back(c);
  s.cams = fit_light_cameras(scene, s.light, s.receivers, eyes);
  s.shadow_maps.resolution = o.shadow_res;
  s.shadow_maps.fit_receivers = !o.full_maps;
  s.shadow_maps.footprint_texels = o.shadow_footprint;
  s.truth = shadow_map_visibility(scene, s.receivers, s.samples, s.cams, s.shadow_maps, &s.truth_ms, &s.truth_stats);
  if (!o.no_rays) s.exact = ray_visibility(rays, scene, s.receivers, s.samples, &s.rays_ms);
  return s;
}

ShadowSamplingRun run_shadow_sampling(const Scene& scene, const RayScene& rays, const ShadowSetting& s,
                                      const ShadowsOptions& o, ShadowSampling sampling) {
  OccluderOptions occ;
  occ.resolution = o.ref_res;
  occ.redundancy = o.redundancy;
  occ.reconstruction = o.reconstruction;
  ShadowSamplingRun run;
  run.occluders = build_occluders(scene, &rays, s.light, s.cams, sampling, occ);
  run.stats = s.truth_stats;
  run.visibility = sampling == ShadowSampling::Geometry
                       ? s.truth
                       : shadow_map_visibility(run.occluders.scene, s.receivers, s.samples, s.cams, s.shadow_maps,
                                               nullptr, &run.stats);
  run.shadow_ms = run.stats.ms;
  return run;
}

void validate(const ShadowsOptions& o) {
  require_above_at_most(o.light_size, 0.0f, 100.0f, "--light-size");
  require_in_range(o.light_samples, 1, 64, "--light-samples");
  check_side(o.ref_res, "--ref-res");
  check_side(o.out_res, "--out-res");
  check_side(o.shadow_res, "--shadow-res");
  require_in_range(o.shadow_footprint, 0.0f, 16.0f, "--shadow-footprint");
  if (o.samplings.empty()) fail_input("--sampling: give at least one");
}

void validate(const ShadowsOptions& options, const Scene& scene) {
  validate(options);
  pick_camera(scene, options.camera, options.out_res, options.out_res);
}

Results run_shadows(const Scene& scene, const ShadowsOptions& o, const StudyOutput& out, Progress*) {
  validate(o);
  const RayScene rays(scene);
  const ShadowSetting s = shadow_setting(scene, rays, pick_camera(scene, o.camera, o.out_res, o.out_res), o);
  Results results;
  Tables t = make_tables(scene, o);
  add_ground_truth(results, t, scene, s, !o.no_rays, out);
  for (ShadowSampling sampling : o.samplings) add_sampling(results, t, scene, rays, s, o, sampling, out);
  results.metrics["light_size"] = o.light_size;
  results.metrics["light_samples"] = double(s.samples.points.size());
  results.metrics["receivers"] = double(s.receivers.count);
  results.metrics["triangles"] = double(scene.triangles.size());
  results.metrics["light_fov_deg"] = s.cams.vfov_deg;
  results.metrics["time_geometry_shadow_ms"] = s.truth_ms;
  results.metrics["shadow_focal_px"] = s.truth_stats.focal_px;
  results.tables.push_back(t.errors);
  if (!o.no_rays) results.tables.push_back(t.rays);
  results.tables.push_back(t.times);
  return results;
}

}  // namespace proxima::study
