// Google Benchmark micro-benchmarks of depth-image sampling: 3 images of
// 1024×1024 (triangle view set, as `proxima sample`) on nest, grass, city and tree, by
// conventional rendering, 3-layer depth peeling and NRR with pixel redundancy, shaded.
// The bound: NRR (pixel) ≤ 2.5× conventional and ≤ 1.3× peeling. Compare the
// three benchmarks of one scene in one run (the machine is shared), e.g.
//   proxima_bench --benchmark_filter='nest' --benchmark_repetitions=5 \
//       --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
// The argument is the thread count; the CPU column is the whole process's CPU time, which
// a loaded machine inflates much less than the wall time.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "proxima/core/parallel.h"
#include "proxima/depthimage/sampling.h"
#include "proxima/depthimage/view_set.h"
#include "proxima/scene/builtin_scenes.h"

namespace {

using namespace proxima;

struct Setup {
  Scene scene;
  std::unique_ptr<RayScene> rays;
  std::vector<Camera> cameras;
  Camera centroid;
};

const Setup& setup(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Setup>> cache;
  auto& s = cache[name];
  if (!s) {
    s = std::make_unique<Setup>();
    s->scene = make_builtin_scene(name);
    s->rays = std::make_unique<RayScene>(s->scene);
    Camera base = s->scene.cameras.front().camera;
    base.width = base.height = 1024;
    const float focus = glm::length(scene_bounds(s->scene).center() - base.position);
    const ViewSet set = make_view_set(ViewShape::Triangle, base, 0.08f * focus, focus);
    for (size_t i = 0; i < set.corners.size(); ++i) s->cameras.push_back(corner_camera(set, i));
    s->centroid = centroid_camera(set);
  }
  return *s;
}

void conventional(benchmark::State& state, const char* scene) {
  const Setup& s = setup(scene);
  const ThreadLimit limit(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(sample_conventional(s.scene, s.cameras, true));
}

void peeling(benchmark::State& state, const char* scene) {
  const Setup& s = setup(scene);
  const ThreadLimit limit(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(sample_peeling(s.scene, s.centroid, 3, true));
}

void nrr_pixel(benchmark::State& state, const char* scene) {
  const Setup& s = setup(scene);
  const ThreadLimit limit(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(sample_nrr(s.scene, s.cameras, Redundancy::Pixel, nullptr, true));
}

#define SAMPLING_BENCH_OF(method, scene) \
  BENCHMARK_CAPTURE(method, scene, #scene)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
#define SAMPLING_BENCH(scene)               \
  SAMPLING_BENCH_OF(conventional, scene)    \
  SAMPLING_BENCH_OF(peeling, scene)         \
  SAMPLING_BENCH_OF(nrr_pixel, scene)

SAMPLING_BENCH(nest)
SAMPLING_BENCH(grass)
SAMPLING_BENCH(city)
SAMPLING_BENCH(tree)

}  // namespace
