// Google Benchmark micro-benchmarks of environment maps with distance on room-reflector
// (filtered cube-map samples, coherent and random directions) and on the paper's two
// Table 1 reflectors, room-reflector and room-car (the frame's reflector visibility and the
// shading pass per method at 1024×768 with a 512² map), 1 thread. The figures in
// docs/RESULTS.md and docs/journal/envmap.md come from `proxima reflect --compare`; these
// are for profiling.
#include <benchmark/benchmark.h>

#include <string>

#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/scene/builtin_scenes.h"

namespace {

using namespace proxima;

struct RoomReflector {
  explicit RoomReflector(const char* name) : scene(make_builtin_scene(name)) {}
  Scene scene;
  RayScene rays{scene};
  std::vector<uint32_t> reflectors = reflective_objects(scene);
  vec3 center = projection_center(scene, reflectors);
  Camera camera = [this] {
    Camera c = scene.cameras.front().camera;
    c.width = 1024;
    c.height = 768;
    return c;
  }();
  DistanceCubeMap map = [this] {
    DistanceCubeMapOptions o;
    o.resolution = 512;
    o.area_light_samples = 1;
    o.exclude = reflectors;
    return render_distance_cube_map(scene, rays, center, o);
  }();
  ReflectorPixels pixels = rasterize_reflector_pixels(scene, camera, reflectors);
};

constexpr const char* kScenes[] = {"room-reflector", "room-car"};

const RoomReflector& room(int64_t index = 0) {
  static const RoomReflector reflector(kScenes[0]);
  static const RoomReflector car(kScenes[1]);
  return index == 0 ? reflector : car;
}

std::vector<vec3> directions(bool coherent) {
  std::vector<vec3> dirs(4096);
  Pcg32 rng(1);
  for (size_t i = 0; i < dirs.size(); ++i) {
    const float a = coherent ? 0.3f + 1e-4f * float(i) : 6.2831853f * rng.next_float();
    const float b = coherent ? 0.1f : 2.0f * rng.next_float() - 1.0f;
    dirs[i] = vec3(std::cos(a), b, std::sin(a));
  }
  return dirs;
}

void BM_SampleCube(benchmark::State& state) {
  const RoomReflector& r = room();
  const std::vector<vec3> dirs = directions(state.range(0) != 0);
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(sample_cube(r.map, dirs[i++ & 4095]));
}
BENCHMARK(BM_SampleCube)->Arg(0)->Arg(1)->ArgName("coherent");

void BM_SampleDistance(benchmark::State& state) {
  const RoomReflector& r = room();
  const std::vector<vec3> dirs = directions(state.range(0) != 0);
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(sample_distance(r.map, dirs[i++ & 4095]));
}
BENCHMARK(BM_SampleDistance)->Arg(0)->Arg(1)->ArgName("coherent");

void BM_ReflectorVisibility(benchmark::State& state) {
  const RoomReflector& r = room(state.range(0));
  ThreadLimit limit(1);
  for (auto _ : state) benchmark::DoNotOptimize(rasterize_reflector_pixels(r.scene, r.camera, r.reflectors));
  state.SetLabel(kScenes[state.range(0)]);
}
BENCHMARK(BM_ReflectorVisibility)->Arg(0)->Arg(1)->ArgName("scene")->Unit(benchmark::kMillisecond);

void BM_ShadeReflector(benchmark::State& state) {
  const RoomReflector& r = room(state.range(1));
  ThreadLimit limit(1);
  EnvmapInputs in;
  in.method = EnvmapMethod(state.range(0));
  in.map = &r.map;
  in.average_distance = average_distance(r.map, 0.0349066f);
  in.rectify.D = 12.0f;
  for (auto _ : state)
    benchmark::DoNotOptimize(shade_reflector_pixels(r.scene, r.rays, r.camera, r.pixels, in));
  state.SetLabel(std::string(kScenes[state.range(1)]) + " " + envmap_method_name(in.method));
}
BENCHMARK(BM_ShadeReflector)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->ArgNames({"method", "scene"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
