// visibility/ benchmarks, 1 thread (the code is serial): BSP → winged-pair build
// per test model, the visibility map per viewpoint along each model's `walk` (20 frames
// spread over the path; 20 iterations = one pass), and the output-sensitivity sweep: the
// floor-1 walk of `building --floors N`, N = 1, 2, 5, 10 (target: < 25 % growth from
// 1 to 10). Map resolution 512² (the map's cost hardly depends on it). Brush-built level:
// build and map of `level-large` (~19k triangles: coplanar overlaps, T-junctions, unwelded
// seams) at 512 × 384 along its walk (target: ≤ 20 ms average, ≤ 100 ms maximum per
// map, subdivision ≤ 1 s). Counters: beams and regions per viewpoint, averaged over the
// iterations.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>

#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/visibility_map.h"

namespace proxima {
namespace {

using namespace proxima::visibility;

struct Built {
  Scene scene;
  ModelPolygons model;
  WingedPair wp;
};

// Model 0..5 = rooms, maze, arena, vcity, floor, building (5 floors), 6 = level-large;
// 100 + N = building with N floors.
Scene make_model(int64_t id) {
  switch (id) {
    case 0: return make_vis_rooms();
    case 1: return make_vis_maze();
    case 2: return make_vis_arena();
    case 3: return make_vis_vcity();
    case 4: return make_vis_floor();
    case 5: return make_vis_building(5);
    case 6: return make_builtin_scene("level-large");
    default: return make_vis_building(int(id - 100));
  }
}

const Built& built(int64_t id) {
  static std::map<int64_t, std::unique_ptr<Built>> cache;
  auto& slot = cache[id];
  if (!slot) {
    slot = std::make_unique<Built>();
    slot->scene = make_model(id);
    slot->model = extract_polygons(slot->scene);
    slot->wp = build_winged_pair(slot->model);
  }
  return *slot;
}

void BM_VisibilityBuild(benchmark::State& state) {
  const Scene scene = make_model(state.range(0));
  const ModelPolygons model = extract_polygons(scene);
  size_t cells = 0;
  for (auto _ : state) {
    WingedPair wp = build_winged_pair(model);
    cells = wp.cells.size();
    benchmark::DoNotOptimize(wp.faces.data());
  }
  state.SetLabel(scene.name);
  state.counters["polygons"] = double(model.polygons.size());
  state.counters["cells"] = double(cells);
}
BENCHMARK(BM_VisibilityBuild)->DenseRange(0, 6)->Unit(benchmark::kMillisecond)->UseRealTime();

void run_maps(benchmark::State& state, const Built& b, int width = 512, int height = 512) {
  const CameraPath& path = b.scene.camera_paths.front();
  constexpr int kViews = 20;
  size_t k = 0;
  double beams = 0, regions = 0, max_ms = 0;
  for (auto _ : state) {
    const int frame = int(k++ % kViews) * (path.frames - 1) / (kViews - 1);
    const Camera cam = camera_at_time(path, frame_time(path, frame), width, height, 1e-3f, 1e4f);
    const VisibilityMap map = trace_visibility_map(b.wp, cam);
    beams += double(map.stats.beams);
    regions += double(map.stats.regions);
    max_ms = std::max(max_ms, map.stats.ms);
  }
  state.SetLabel(b.scene.name);
  state.counters["beams"] = benchmark::Counter(beams, benchmark::Counter::kAvgIterations);
  state.counters["regions"] = benchmark::Counter(regions, benchmark::Counter::kAvgIterations);
  state.counters["map_ms_max"] = max_ms;
}

void BM_VisibilityMap(benchmark::State& state) { run_maps(state, built(state.range(0))); }
BENCHMARK(BM_VisibilityMap)->DenseRange(0, 5)->Iterations(20)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_VisibilityLevelMap(benchmark::State& state) { run_maps(state, built(6), 512, 384); }
BENCHMARK(BM_VisibilityLevelMap)->Iterations(20)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_VisibilityFloors(benchmark::State& state) { run_maps(state, built(100 + state.range(0))); }
BENCHMARK(BM_VisibilityFloors)->Arg(1)->Arg(2)->Arg(5)->Arg(10)->Iterations(20)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace proxima
