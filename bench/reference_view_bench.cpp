// The reference render of one view as the Python module's render_reference runs it: item
// buffer + reference image on a scene whose BVH is already built, 512² from the scene's
// first camera, default sampling. bench/python/render_overhead.py times the Python call
// against this one, interleaved. Argument: scene (0 = cornell, 1 = living-room).
#include <benchmark/benchmark.h>

#include "proxima/scene/camera_select.h"
#include "proxima/scene/load.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima {
namespace {

void BM_ReferenceView(benchmark::State& state) {
  const Scene scene = load_scene(state.range(0) == 0 ? "cornell" : "living-room");
  const RayScene rays(scene);
  const Camera camera = pick_camera(scene, {}, 512, 512);
  const ReferenceOptions options;
  for (auto _ : state) {
    ItemBuffer item = trace_item_buffer(scene, rays, camera);
    ImageF color = render_reference(scene, rays, camera, options);
    benchmark::DoNotOptimize(item.triangle.data().data());
    benchmark::DoNotOptimize(color.data().data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * 512 * 512);
}
BENCHMARK(BM_ReferenceView)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace proxima
