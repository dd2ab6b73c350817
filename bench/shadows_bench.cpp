// Google Benchmark of soft shadows from reconstructed depth images (thesis
// ch. 3 §3.4.3, Figure 20): the time of ONE shadow map (rasterized depth, 1024², from the
// light's centre) of the original grass geometry vs of its NRR + hybrid reconstruction
// (four 1024² reference images from the light corners, light size 1) as the grass grows
// from 50k to 3M triangles. The reconstruction is built untimed in the fixture; its size
// depends on the reference images, not on the scene, so its time stays flat while the
// geometry's grows — the crossover of Figure 20. Arguments: grass blades (12 triangles each).
//   build/proxima_bench --benchmark_filter=ShadowMap
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "proxima/raster/rasterizer.h"
#include "proxima/scene/sampling_scenes.h"
#include "proxima/shadows/occluders.h"

namespace {

using namespace proxima;

constexpr int kMapRes = 1024;
constexpr int kRefRes = 1024;

struct GrassSetup {
  Scene scene;
  Scene reconstruction;
  LightCameras cams;
  Camera map_camera;
};

const GrassSetup& grass(int blades) {
  static std::map<int, std::unique_ptr<GrassSetup>> cache;
  auto& slot = cache[blades];
  if (!slot) {
    slot = std::make_unique<GrassSetup>();
    GrassSetup& g = *slot;
    g.scene = make_grass_scene(blades);
    const AreaLight light = shadow_light(g.scene, 1.0f);
    const Camera view = look_at(g.scene.cameras[0].camera.position, vec3(0, 0.1f, 0), vec3(0, 1, 0),
                                g.scene.cameras[0].camera.vfov_deg, 256, 256, 0.01f, 200.0f);
    const Receivers receivers = render_receivers(g.scene, view);
    std::vector<vec3> eyes = light_samples(light, 16).points;
    for (const vec3& c : light_corners(light)) eyes.push_back(c);
    g.cams = fit_light_cameras(g.scene, light, receivers, eyes);
    g.map_camera = light_camera(g.cams, light.point(0.5f, 0.5f), kMapRes);
    OccluderOptions o;
    o.resolution = kRefRes;
    g.reconstruction = build_occluders(g.scene, nullptr, light, g.cams, ShadowSampling::Nrr, o).scene;
  }
  return *slot;
}

void shadow_map(benchmark::State& state, bool reconstructed) {
  const GrassSetup& g = grass(int(state.range(0)));
  const Scene& occluders = reconstructed ? g.reconstruction : g.scene;
  RasterOptions o;
  o.outputs = kRasterDepth;
  const std::vector<Bounds3> bounds = raster_object_bounds(occluders);
  o.object_bounds = bounds;
  RasterImages map;
  for (auto _ : state) {
    rasterize(occluders, g.map_camera, o, map, AcceptAllFragments{});
    benchmark::DoNotOptimize(map.depth.data().data());
  }
  state.counters["scene_triangles"] = double(g.scene.triangles.size());
  state.counters["occluder_triangles"] = double(occluders.triangles.size());
}

void BM_ShadowMapGeometry(benchmark::State& state) { shadow_map(state, false); }
void BM_ShadowMapReconstruction(benchmark::State& state) { shadow_map(state, true); }

// ≈ 50k, 200k, 750k, 1.5M, 3M triangles.
#define GRASS_SIZES Arg(4166)->Arg(16666)->Arg(62500)->Arg(125000)->Arg(250000)
BENCHMARK(BM_ShadowMapGeometry)->GRASS_SIZES->Unit(benchmark::kMillisecond)->MinTime(0.5);
BENCHMARK(BM_ShadowMapReconstruction)->GRASS_SIZES->Unit(benchmark::kMillisecond)->MinTime(0.5);

}  // namespace
