// Google Benchmark micro-benchmarks of the rasterizer: living-room at 1024×1024 from its
// first camera, depth + id and G-buffer, 1 and 2 threads. The figures `proxima bench
// raster` reports come from bench_raster() (raster_bench.h); these are for profiling.
#include <benchmark/benchmark.h>

#include "proxima/core/parallel.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/scene/builtin_scenes.h"

namespace {

using namespace proxima;

struct LivingRoom {
  Scene scene = make_builtin_scene("living-room");
  std::vector<Bounds3> bounds = raster_object_bounds(scene);
  Camera camera = [this] {
    Camera c = scene.cameras.front().camera;
    c.width = c.height = 1024;
    return c;
  }();
};

const LivingRoom& living_room() {
  static const LivingRoom scene;
  return scene;
}

void raster_frame(benchmark::State& state, uint32_t outputs) {
  const LivingRoom& lr = living_room();
  ThreadLimit limit(int(state.range(0)));
  RasterOptions options;
  options.outputs = outputs;
  options.object_bounds = lr.bounds;
  RasterImages images;
  for (auto _ : state) {
    rasterize(lr.scene, lr.camera, options, images, AcceptAllFragments{});
    benchmark::ClobberMemory();
  }
  state.counters["tris_per_s"] =
      benchmark::Counter(double(lr.scene.triangles.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_RasterDepthId(benchmark::State& state) { raster_frame(state, kRasterDepthId); }
void BM_RasterGBuffer(benchmark::State& state) { raster_frame(state, kRasterGBuffer); }

BENCHMARK(BM_RasterDepthId)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RasterGBuffer)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
