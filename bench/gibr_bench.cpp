// gibr/ novel-view benchmark: render_novel_view at 640×480 with 2 × 2 samples per
// pixel (`proxima gibr --novel-ss 0`), over the 10 views `proxima gibr --views path --frames 10`
// renders, on the visibility-map radiance maps `proxima gibr --photos 100` builds; the fast
// path beside the plain one (NovelViewOptions::fast, same bits) in one run. Scene 0..2 =
// rooms, floor, vcity. One iteration = the 10 views; counters: per-frame medians of wall,
// process CPU (all threads), raster and blend ms. Threads: all cores (TBB).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>
#include <map>
#include <memory>
#include <vector>

#include "proxima/gibr/gibr_model.h"
#include "proxima/gibr/novel_view.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/load.h"

namespace proxima::gibr {
namespace {

struct Built {
  GibrModel g;
  std::vector<Camera> views;
};

const Built& built(int64_t id) {
  static std::map<int64_t, std::unique_ptr<Built>> cache;
  auto& slot = cache[id];
  if (!slot) {
    slot = std::make_unique<Built>();
    const Scene scene = load_scene(id == 0 ? "rooms" : id == 1 ? "floor" : "vcity");
    slot->g = build_gibr_model(scene, {});
    const CameraPath& path = scene.camera_paths.front();
    const float t0 = path.keys.front().time, t1 = path.keys.back().time;
    for (int i = 0; i < 10; ++i)
      slot->views.push_back(camera_at_time(path, t0 + (t1 - t0) * float(i) / 9.0f, 640, 480, 0.01f, slot->g.far));
  }
  return *slot;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void BM_GibrNovelView(benchmark::State& state) {
  const Built& b = built(state.range(0));
  NovelViewOptions o;
  o.supersample = 2;
  o.fast = state.range(1) != 0;
  std::vector<double> wall, cpu, raster, blend;
  NovelViewScratch scratch;  // raster buffers kept between frames, as a viewer would
  for (auto _ : state)
    for (const Camera& cam : b.views) {
      const std::clock_t c0 = std::clock();
      const NovelView nv = render_novel_view(b.g.scene, b.g.model, b.g.maps, cam, o, &scratch);
      cpu.push_back(1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC);
      wall.push_back(nv.raster_ms + nv.blend_ms);
      raster.push_back(nv.raster_ms);
      blend.push_back(nv.blend_ms);
    }
  state.counters["frame_ms"] = median(wall);
  state.counters["frame_cpu_ms"] = median(cpu);
  state.counters["raster_ms"] = median(raster);
  state.counters["blend_ms"] = median(blend);
}
// Plain and fast alternate, three rounds per scene: load changes hit both alike.
BENCHMARK(BM_GibrNovelView)
    ->Apply([](benchmark::internal::Benchmark* b) {
      for (int scene = 0; scene < 3; ++scene)
        for (int round = 0; round < 3; ++round) b->Args({scene, 0})->Args({scene, 1});
    })
    ->ArgNames({"scene", "fast"})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
}  // namespace proxima::gibr
