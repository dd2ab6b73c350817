// Steps 1–2 of the soft shadows alone (occluders.h, build_occluders): the NRR reference
// images from the light's corners and their offset images, then the hybrid
// reconstruction, at the demo's settings (light size 1, 8×8 samples, 256² receivers, NRR
// 512²) on grass of ≈ 1M and 10M triangles: the part of the depth-image method that
// grows with the scene (bench/shadows_crossover_bench.cpp for the whole comparison).
// Counters: medians over the repetitions of step 1, step 2 and process-CPU ms; the
// reference samples and occluder triangles (equal for any change that keeps the bits).
// Arguments: grass blades (12 triangles each), repetitions, threads.
//   build/release/proxima_bench --benchmark_filter=ShadowsStep1
#include <benchmark/benchmark.h>

#include <vector>

#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/sampling_scenes.h"
#include "proxima/shadows/light_visibility.h"
#include "proxima/shadows/occluders.h"

namespace {

using namespace proxima;

void BM_ShadowsStep1(benchmark::State& state) {
  const int blades = int(state.range(0)), reps = int(state.range(1));
  ThreadLimit limit(int(state.range(2)));
  const Scene scene = make_grass_scene(blades);
  const Camera view = pick_camera(scene, CameraChoice{}, 256, 256);
  const AreaLight light = shadow_light(scene, 1.0f);
  const Receivers receivers = render_receivers(scene, view);
  std::vector<vec3> eyes = light_samples(light, 8).points;
  for (const vec3& c : light_corners(light)) eyes.push_back(c);
  const LightCameras cams = fit_light_cameras(scene, light, receivers, eyes);
  OccluderOptions oo;
  oo.resolution = 512;
  std::vector<double> reference, reconstruct, cpu;
  Occluders occ;
  for (auto _ : state) {
    for (int r = 0; r < reps; ++r) {
      const double c0 = process_cpu_ms();
      occ = build_occluders(scene, nullptr, light, cams, ShadowSampling::Nrr, oo);
      cpu.push_back(process_cpu_ms() - c0);
      reference.push_back(occ.reference_ms);
      reconstruct.push_back(occ.reconstruct_ms);
    }
  }
  auto& c = state.counters;
  c["triangles"] = double(scene.triangles.size());
  c["reference_ms"] = median(reference);
  c["reconstruct_ms"] = median(reconstruct);
  c["steps12_cpu_ms"] = median(cpu);
  c["samples"] = double(occ.samples);
  c["occluder_triangles"] = double(occ.scene.triangles.size());
}

BENCHMARK(BM_ShadowsStep1)
    ->ArgsProduct({{83333, 833334}, {3}, {2}})
    ->ArgNames({"blades", "reps", "threads"})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
