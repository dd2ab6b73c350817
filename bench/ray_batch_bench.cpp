// Batched ray casts (trace/ray_batch.h) on 1M random rays from inside the built-in
// living-room, the workload of bench/python/rays_vs_open3d.py without Python: the batch
// (coherent trace order, hit records) against the same rays traced one by one in input
// order (RayScene::intersect over a span, t/id/uv only). Argument: threads (ThreadLimit).
// items_per_second = rays/s of wall time.
#include <benchmark/benchmark.h>

#include <vector>

#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/trace/ray_batch.h"

namespace proxima {
namespace {

constexpr size_t kRays = 1'000'000;

struct Workload {
  Scene scene = make_builtin_scene("living-room");
  RayScene rays{scene};
  LargeBuffer<TriangleHitRecord> records = triangle_hit_records(scene);
  std::vector<vec3> origins, directions;

  // Origins uniform in the scene's bounds shrunk by 10 % on each side, directions uniform
  // on the sphere (normalized Gaussian vectors).
  Workload() {
    vec3 lo(kInf), hi(-kInf);
    for (const vec3& p : scene.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const vec3 pad = 0.1f * (hi - lo);
    Pcg32 rng(1);
    for (size_t i = 0; i < kRays; ++i) {
      origins.push_back(lo + pad +
                        vec3(rng.next_float(), rng.next_float(), rng.next_float()) * (hi - lo - 2.0f * pad));
      vec3 d;
      do d = vec3(rng.next_float(), rng.next_float(), rng.next_float()) * 2.0f - 1.0f;
      while (glm::dot(d, d) > 1.0f || glm::dot(d, d) < 1e-6f);
      directions.push_back(glm::normalize(d));
    }
  }
};

const Workload& workload() {
  static const Workload w;
  return w;
}

void BM_RayBatch(benchmark::State& state) {
  const Workload& w = workload();
  ThreadLimit limit(int(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(cast_ray_batch(w.records, w.rays, w.origins, w.directions));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kRays));
}
BENCHMARK(BM_RayBatch)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RaysInInputOrder(benchmark::State& state) {
  const Workload& w = workload();
  ThreadLimit limit(int(state.range(0)));
  std::vector<Ray> rays;
  for (size_t i = 0; i < kRays; ++i) rays.push_back(Ray{w.origins[i], w.directions[i], 0.0f, kInf});
  std::vector<Hit> hits(kRays);
  for (auto _ : state) {
    w.rays.intersect(rays, hits);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kRays));
}
BENCHMARK(BM_RaysInInputOrder)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace proxima
