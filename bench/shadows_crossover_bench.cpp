// Soft shadows from depth images against exact Embree shadow rays, both in one run on the
// same receivers and light samples (docs/shadows.md, "Against Embree"): the demo's settings
// (light size 1, 8×8 samples, 256² receivers from the scene's main camera, NRR reference
// images 512² with the hybrid reconstruction, shadow-map density of 1024²) on city and on
// grass from 50k to 20M triangles. Per repetition, interleaved: the depth-image method
// (step 1 reference images, step 2 reconstruction with merged planar runs, step 3 with
// fitted maps drawn one per task by the depth-only rasterizer, only the triangles over
// texels a receiver reads), step 3 as it was (whole-field 1024² maps of the unmerged
// reconstruction, one after another through the tiled rasterizer),
// the Embree BVH build and the shadow rays. Counters are medians over the repetitions;
// visibility errors (0–255) are against the rays. Arguments: grass blades (12 triangles
// each; 0 = city), repetitions, threads.
//   build/release/proxima_bench --benchmark_filter=SoftShadowsVsRays   (scripts/shadows-bench.sh)
#include <benchmark/benchmark.h>
#include <sys/resource.h>

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

double max_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;
}

// Wall-clock and process-CPU milliseconds per phase and repetition. On a shared machine
// the CPU times are the steadier figures (another process's load does not count).
struct Times {
  std::vector<double> reference, reconstruct, shadow, shadow_today, bvh, rays;
  std::vector<double> steps12_cpu, shadow_cpu, shadow_today_cpu, bvh_cpu, rays_cpu;
};

void BM_SoftShadowsVsRays(benchmark::State& state) {
  const int blades = int(state.range(0)), reps = int(state.range(1));
  ThreadLimit limit(int(state.range(2)));
  const Scene scene = blades > 0 ? make_grass_scene(blades) : make_city_scene();
  const Camera view = pick_camera(scene, CameraChoice{}, 256, 256);  // as `proxima shadows --out-res 256`
  const AreaLight light = shadow_light(scene, 1.0f);
  const LightSamples samples = light_samples(light, 8);
  const Receivers receivers = render_receivers(scene, view);
  std::vector<vec3> eyes = samples.points;
  for (const vec3& c : light_corners(light)) eyes.push_back(c);
  const LightCameras cams = fit_light_cameras(scene, light, receivers, eyes);
  OccluderOptions oo;
  oo.resolution = 512;
  // Step 3 as it was ran on the unmerged reconstruction (built once: it is deterministic).
  OccluderOptions unmerged = oo;
  unmerged.merge_planar_runs = false;
  const Occluders occ_today = build_occluders(scene, nullptr, light, cams, ShadowSampling::Nrr, unmerged);
  ShadowMapOptions fitted, today;
  today.fit_receivers = false;
  today.per_map_tasks = false;
  Times t;
  LightVisibility v_fitted, v_today, v_rays;
  ShadowMapStats st_fitted, st_today;
  size_t occluder_triangles = 0, occluder_vertices = 0;
  for (auto _ : state) {
    t = Times{};
    for (int r = 0; r < reps; ++r) {
      double cpu = process_cpu_ms();
      const Occluders occ = build_occluders(scene, nullptr, light, cams, ShadowSampling::Nrr, oo);
      t.steps12_cpu.push_back(process_cpu_ms() - cpu);
      occluder_triangles = occ.scene.triangles.size();
      occluder_vertices = occ.scene.positions.size();
      t.reference.push_back(occ.reference_ms);
      t.reconstruct.push_back(occ.reconstruct_ms);
      // Alternate which step-3 variant goes first.
      for (int k = 0; k < 2; ++k) {
        cpu = process_cpu_ms();
        if ((k == 0) == (r % 2 == 0)) {
          v_fitted = shadow_map_visibility(occ.scene, receivers, samples, cams, fitted, nullptr, &st_fitted);
          t.shadow_cpu.push_back(process_cpu_ms() - cpu);
        } else {
          v_today = shadow_map_visibility(occ_today.scene, receivers, samples, cams, today, nullptr, &st_today);
          t.shadow_today_cpu.push_back(process_cpu_ms() - cpu);
        }
      }
      t.shadow.push_back(st_fitted.ms);
      t.shadow_today.push_back(st_today.ms);
      Stopwatch build;
      cpu = process_cpu_ms();
      const RayScene rays(scene);
      t.bvh.push_back(build.elapsed_ms());
      t.bvh_cpu.push_back(process_cpu_ms() - cpu);
      double rays_ms = 0.0;
      cpu = process_cpu_ms();
      v_rays = ray_visibility(rays, scene, receivers, samples, &rays_ms);
      t.rays_cpu.push_back(process_cpu_ms() - cpu);
      t.rays.push_back(rays_ms);
    }
  }
  const double reference = median(t.reference), reconstruct = median(t.reconstruct), shadow = median(t.shadow);
  const double depth_total = reference + reconstruct + shadow, bvh = median(t.bvh), rays = median(t.rays);
  auto& c = state.counters;
  c["triangles"] = double(scene.triangles.size());
  c["occluder_triangles"] = double(occluder_triangles);
  c["occluder_triangles_today"] = double(occ_today.scene.triangles.size());
  c["occluder_vertices"] = double(occluder_vertices);
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
  const double depth_cpu = median(t.steps12_cpu) + median(t.shadow_cpu);
  c["depth_image_cpu_ms"] = depth_cpu;
  c["steps12_cpu_ms"] = median(t.steps12_cpu);
  c["shadow_cpu_ms"] = median(t.shadow_cpu);
  c["shadow_today_cpu_ms"] = median(t.shadow_today_cpu);
  c["shadow_speedup_cpu"] = median(t.shadow_today_cpu) / median(t.shadow_cpu);
  c["bvh_cpu_ms"] = median(t.bvh_cpu);
  c["rays_cpu_ms"] = median(t.rays_cpu);
  c["ratio_static_cpu"] = median(t.rays_cpu) / depth_cpu;
  c["ratio_dynamic_cpu"] = (median(t.bvh_cpu) + median(t.rays_cpu)) / depth_cpu;
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

// city; grass ≈ 50k, 200k, 1M, 3M, 10M, 20M triangles; 5 repetitions; 2 threads.
BENCHMARK(BM_SoftShadowsVsRays)
    ->ArgsProduct({{0, 4166, 16666, 83333, 250000, 833334, 1666667}, {5}, {2}})
    ->ArgNames({"blades", "reps", "threads"})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
