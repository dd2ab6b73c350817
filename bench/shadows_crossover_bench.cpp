// Soft shadows from depth images against exact Embree shadow rays, both in one run on the
// same receivers and light samples (docs/shadows.md, "Against Embree"): the demo's settings
// (light size 1, 8×8 samples, 256² receivers from the scene's main camera, NRR reference
// images 512² with the hybrid reconstruction, shadow-map density of 1024²) on city and on
// grass from 50k to 10M triangles. Per repetition, interleaved: the depth-image method
// (step 1 reference images, step 2 reconstruction, step 3 with fitted maps), step 3 as it
// was (whole-field 1024² maps, ShadowMapOptions::fit_receivers off) on the same occluders,
// the Embree BVH build and the shadow rays. Counters are medians over the repetitions;
// visibility errors (0–255) are against the rays. Arguments: grass blades (12 triangles
// each; 0 = city), repetitions, threads.
//   build/release/proxima_bench --benchmark_filter=SoftShadowsVsRays   (scripts/shadows-bench.sh)
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <vector>

#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/sampling_scenes.h"
#include "proxima/shadows/light_visibility.h"
#include "proxima/shadows/occluders.h"
#include "proxima/shadows/shadow_error.h"
#include "proxima/trace/ray_scene.h"

namespace {

using namespace proxima;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

double max_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;
}

struct Times {
  std::vector<double> reference, reconstruct, shadow, shadow_today, bvh, rays;
};

void BM_SoftShadowsVsRays(benchmark::State& state) {
  const int blades = int(state.range(0)), reps = int(state.range(1));
  ThreadLimit limit(int(state.range(2)));
  const Scene scene = blades > 0 ? make_grass_scene(blades) : make_city_scene();
  const Camera view = pick_camera(scene, CameraChoice{}, 256, 256);  // as `proxima shadows --out-res 256`
  const AreaLight light = shadow_light(scene, 1.0f);
  const std::vector<vec3> samples = light_samples(light, 8);
  const Receivers receivers = render_receivers(scene, view);
  std::vector<vec3> eyes = samples;
  for (const vec3& c : light_corners(light)) eyes.push_back(c);
  const LightCameras cams = fit_light_cameras(scene, light, receivers, eyes);
  OccluderOptions oo;
  oo.resolution = 512;
  ShadowMapOptions fitted, today;
  today.fit_receivers = false;
  Times t;
  LightVisibility v_fitted, v_today, v_rays;
  ShadowMapStats st_fitted, st_today;
  size_t occluder_triangles = 0;
  for (auto _ : state) {
    t = Times{};
    for (int r = 0; r < reps; ++r) {
      const Occluders occ = build_occluders(scene, nullptr, light, cams, ShadowSampling::Nrr, oo);
      occluder_triangles = occ.scene.triangles.size();
      t.reference.push_back(occ.reference_ms);
      t.reconstruct.push_back(occ.reconstruct_ms);
      // Alternate which step-3 variant goes first.
      for (int k = 0; k < 2; ++k) {
        if ((k == 0) == (r % 2 == 0))
          v_fitted = shadow_map_visibility(occ.scene, receivers, samples, cams, fitted, nullptr, &st_fitted);
        else
          v_today = shadow_map_visibility(occ.scene, receivers, samples, cams, today, nullptr, &st_today);
      }
      t.shadow.push_back(st_fitted.ms);
      t.shadow_today.push_back(st_today.ms);
      Stopwatch build;
      const RayScene rays(scene);
      t.bvh.push_back(build.elapsed_ms());
      double rays_ms = 0.0;
      v_rays = ray_visibility(rays, scene, receivers, samples, &rays_ms);
      t.rays.push_back(rays_ms);
    }
  }
  const double reference = median(t.reference), reconstruct = median(t.reconstruct), shadow = median(t.shadow);
  const double depth_total = reference + reconstruct + shadow, bvh = median(t.bvh), rays = median(t.rays);
  auto& c = state.counters;
  c["triangles"] = double(scene.triangles.size());
  c["occluder_triangles"] = double(occluder_triangles);
  c["receivers"] = double(receivers.count);
  c["reference_ms"] = reference;
  c["reconstruct_ms"] = reconstruct;
  c["shadow_ms"] = shadow;
  c["shadow_today_ms"] = median(t.shadow_today);
  c["shadow_speedup"] = median(t.shadow_today) / shadow;
  c["depth_image_ms"] = depth_total;
  c["bvh_ms"] = bvh;
  c["rays_ms"] = rays;
  c["ratio_static"] = rays / depth_total;           // > 1: the depth-image method wins
  c["ratio_dynamic"] = (bvh + rays) / depth_total;  // the BVH rebuilt for a changed scene
  c["fit_ms"] = st_fitted.fit_ms;
  c["map_raster_ms"] = st_fitted.raster_ms;
  c["map_test_ms"] = st_fitted.test_ms;
  c["texels"] = double(st_fitted.texels);
  c["texels_today"] = double(st_today.texels);
  c["triangles_drawn"] = double(st_fitted.triangles_drawn);
  c["triangles_drawn_today"] = double(st_today.triangles_drawn);
  c["receivers_outside"] = double(st_fitted.receivers_outside);
  c["vis_error_rays"] = compare_visibility(v_fitted, v_rays, receivers).visibility_mean;
  c["vis_error_rays_today"] = compare_visibility(v_today, v_rays, receivers).visibility_mean;
  c["fitted_vs_today_vis"] = compare_visibility(v_fitted, v_today, receivers).visibility_mean;
  c["max_rss_mb"] = max_rss_mb();
}

// city; grass ≈ 50k, 200k, 1M, 3M, 10M triangles; 5 repetitions; 2 threads.
BENCHMARK(BM_SoftShadowsVsRays)
    ->ArgsProduct({{0, 4166, 16666, 83333, 250000, 833334}, {5}, {2}})
    ->ArgNames({"blades", "reps", "threads"})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
