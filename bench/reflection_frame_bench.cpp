// The shared first pass of every reflection method and its Embree reference,
// prepare_reflection_frame (G-buffer, base shading, ray set-up), at the settings of the
// two benches that include it: the cluster bench's (scripts/cluster-bench.sh: walk frames 0,
// 300, 600 of 900 at 512² with 2×2 samples, object bounds as the cluster study passes them)
// and temporal reuse's (walk frame 105 of 500 at 1024², one sample). Counters: process CPU
// ms per frame and the frame's wall-clock phases (raster, shading, rays). BM_ReflectionClustering
// times the cluster method's clustering step on the cluster bench's frames.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/reflection_clustering.h"
#include "proxima/reflect/reflection_frame.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"

namespace {

using namespace proxima;

const char* const kScenes[] = {"living-room", "bathroom"};

struct Setting {
  int side, supersample, frames;
  std::vector<int> indices;
  bool bounds;
};

const Setting kSettings[] = {{512, 2, 900, {0, 300, 600}, true}, {1024, 1, 500, {105}, false}};

std::vector<Camera> walk_cameras(const Scene& scene, const Setting& s) {
  const CameraPath& path = scene.camera_paths[size_t(find_camera_path(scene, "walk"))];
  const float t0 = path.keys.front().time, t1 = path.keys.back().time;
  const float far = scene_far_plane(scene);
  std::vector<Camera> cameras;
  for (int i : s.indices)
    cameras.push_back(camera_at_time(path, t0 + float(i) * (t1 - t0) / float(s.frames - 1), s.side, s.side, 0.01f, far));
  return cameras;
}

void BM_ReflectionFrameShared(benchmark::State& state) {
  const Scene scene = make_builtin_scene(kScenes[state.range(0)]);
  const Setting& s = kSettings[state.range(1)];
  ThreadLimit limit(int(state.range(2)));
  const std::vector<Camera> cameras = walk_cameras(scene, s);
  ReflectionOptions ro;
  ro.supersample = s.supersample;
  ro.glossy_rays = 8;
  double cpu = 0.0, raster = 0.0, shading = 0.0, rays = 0.0;
  size_t calls = 0, samples = 0;
  for (auto _ : state) {
    for (const Camera& c : cameras) {
      const double before = process_cpu_ms();
      const std::vector<Bounds3> bounds = s.bounds ? raster_object_bounds(scene) : std::vector<Bounds3>{};
      const ReflectionFrame f = prepare_reflection_frame(scene, c, ro, bounds);
      cpu += process_cpu_ms() - before;
      raster += f.raster_ms, shading += f.shading_ms, rays += f.rays_ms;
      samples += f.sample_count();
      ++calls;
    }
  }
  const double n = double(std::max<size_t>(calls, 1));
  state.counters["cpu_ms"] = cpu / n;
  state.counters["raster_ms"] = raster / n;
  state.counters["shading_ms"] = shading / n;
  state.counters["rays_ms"] = rays / n;
  state.counters["reflective"] = double(samples) / n;
}

// The rest of the cluster method's first phase (what its "G-buffer + clustering" adds to
// the shared pass): cluster_reflections on each frame's samples, default options.
void BM_ReflectionClustering(benchmark::State& state) {
  const Scene scene = make_builtin_scene(kScenes[state.range(0)]);
  const Setting& s = kSettings[0];
  ThreadLimit limit(int(state.range(1)));
  ReflectionOptions ro;
  ro.supersample = s.supersample;
  ro.glossy_rays = 8;
  std::vector<ReflectionFrame> frames;
  for (const Camera& c : walk_cameras(scene, s)) frames.push_back(prepare_reflection_frame(scene, c, ro));
  double cpu = 0.0;
  size_t calls = 0, clusters = 0;
  for (auto _ : state) {
    for (const ReflectionFrame& f : frames) {
      const double before = process_cpu_ms();
      clusters += cluster_reflections(f.normal, f.reflector, ClusteringOptions{}).count();
      cpu += process_cpu_ms() - before;
      ++calls;
    }
  }
  state.counters["cpu_ms"] = cpu / double(std::max<size_t>(calls, 1));
  state.counters["clusters"] = double(clusters) / double(std::max<size_t>(calls, 1));
}

}  // namespace

// scene: 0 living-room, 1 bathroom; setting: 0 the cluster bench's, 1 temporal's.
BENCHMARK(BM_ReflectionFrameShared)
    ->ArgsProduct({{0, 1}, {0, 1}, {1, 2}})
    ->ArgNames({"scene", "setting", "threads"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReflectionClustering)->ArgsProduct({{0, 1}, {1, 2}})->ArgNames({"scene", "threads"})->Unit(benchmark::kMillisecond);
