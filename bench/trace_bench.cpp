// trace/ micro-benchmarks: BVH build and refit, primary, mirror-reflection and shadow rays
// per second (items_per_second = rays/s of wall time), and a reference render (pixels/s).
// Arguments: scene (0 = sphere field, 1 = built-in living-room), threads (ThreadLimit).
// The sphere field (16×16 UV spheres of ≈4k triangles on a floor, ≈1M triangles) is
// generated here so its numbers do not move when the built-in scenes change.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/shading.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima {
namespace {

Mesh uv_sphere(vec3 center, float radius, int segments, int rings) {
  Mesh m;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      float theta = kPi * float(r) / float(rings), phi = 2.0f * kPi * float(s) / float(segments);
      vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      m.positions.push_back(center + radius * n);
      m.normals.push_back(n);
      m.uvs.push_back(vec2(0.0f));
    }
  auto id = [&](int r, int s) { return uint32_t(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      if (r != 0) m.triangles.push_back(uvec3(id(r, s), id(r + 1, s), id(r, s + 1)));  // poles: skip
      if (r != rings - 1) m.triangles.push_back(uvec3(id(r, s + 1), id(r + 1, s), id(r + 1, s + 1)));
    }
  return m;
}

const Scene& sphere_field() {
  static const Scene scene = [] {
    Scene s;
    Material glossy;
    glossy.diffuse = vec3(0.5f);
    glossy.specular = 0.5f;
    glossy.gloss = 0.2f;
    uint32_t mat = add_material(s, glossy);
    Mesh floor;
    floor.positions = {vec3(-20, 0, 20), vec3(20, 0, 20), vec3(20, 0, -20), vec3(-20, 0, -20)};
    floor.normals.assign(4, vec3(0, 1, 0));
    floor.uvs.assign(4, vec2(0.0f));
    floor.triangles = {uvec3(0, 1, 2), uvec3(0, 2, 3)};
    add_object(s, floor, "floor", mat);
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j)
        add_object(s, uv_sphere(vec3(float(i) - 7.5f, 0.45f, float(j) - 7.5f), 0.45f, 64, 32), "sphere", mat);
    s.point_lights.push_back(PointLight{vec3(3, 10, 4), vec3(100.0f)});
    return s;
  }();
  return scene;
}

const Scene& living_room() {
  static const Scene scene = make_builtin_scene("living-room");
  return scene;
}

const Scene& bench_scene(int64_t index) { return index == 0 ? sphere_field() : living_room(); }

Camera bench_camera(int64_t scene, int size) {
  if (scene == 0) return look_at(vec3(0, 6, 12), vec3(0, 0, 0), vec3(0, 1, 0), 60.0f, size, size);
  Camera cam = living_room().cameras.at(0).camera;
  cam.width = size;
  cam.height = size;
  return cam;
}

std::vector<Ray> primary_rays(const Camera& cam) {
  std::vector<Ray> rays;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      rays.push_back(ray_through(cam, vec2(float(x) + 0.5f, float(y) + 0.5f)));
  return rays;
}

// A point on the scene's first light.
vec3 light_position(const Scene& scene) {
  if (!scene.point_lights.empty()) return scene.point_lights[0].position;
  const AreaLight& a = scene.area_lights.at(0);
  return a.point(0.5f, 0.5f);
}

// Mirror rays (or, with `to_light`, shadow segments) from the primary hits.
std::vector<Ray> secondary_rays(const Scene& scene, const RayScene& rs, const std::vector<Ray>& primary,
                                bool to_light) {
  std::vector<Hit> hits(primary.size());
  rs.intersect(primary, hits);
  std::vector<Ray> rays;
  for (size_t i = 0; i < primary.size(); ++i) {
    if (!hits[i].valid()) continue;
    vec3 n = triangle_normal(scene, hits[i].triangle);
    if (glm::dot(n, primary[i].dir) > 0.0f) n = -n;
    vec3 p = primary[i].origin + hits[i].t * primary[i].dir + 1e-4f * n;
    if (to_light)
      rays.push_back(Ray{p, light_position(scene) - p, 0.0f, 1.0f});
    else
      rays.push_back(
          Ray{p, reflect(primary[i].dir, shading_normal(scene, hits[i].triangle, hits[i].u, hits[i].v)), 0.0f,
              kInf});
  }
  return rays;
}

void BM_BvhBuild(benchmark::State& state) {
  ThreadLimit limit(int(state.range(1)));
  const Scene& scene = bench_scene(state.range(0));
  double ms = 0.0;
  for (auto _ : state) {
    RayScene rs(scene);
    ms = rs.build_ms();
  }
  state.counters["triangles"] = double(scene.triangles.size());
  state.counters["build_ms"] = ms;
}
BENCHMARK(BM_BvhBuild)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Refit(benchmark::State& state) {
  ThreadLimit limit(int(state.range(1)));
  const Scene& scene = bench_scene(state.range(0));
  RayScene rs(scene);
  Scene moved = scene;
  rs.update(moved);  // the first update builds the refittable BVH; time the refits
  float dy = 0.0f;
  for (auto _ : state) {
    dy += 0.01f;
    state.PauseTiming();
    for (size_t i = 0; i < moved.positions.size(); ++i) moved.positions[i].y = scene.positions[i].y + dy;
    state.ResumeTiming();
    rs.update(moved);
  }
}
BENCHMARK(BM_Refit)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void run_rays(benchmark::State& state, const std::vector<Ray>& rays, const RayScene& rs, bool occlusion) {
  std::vector<Hit> hits(rays.size());
  std::vector<uint8_t> blocked(rays.size());
  for (auto _ : state) {
    if (occlusion)
      rs.occluded(rays, blocked);
    else
      rs.intersect(rays, hits);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays.size()));
}

void BM_PrimaryRays(benchmark::State& state) {
  ThreadLimit limit(int(state.range(1)));
  RayScene rs(bench_scene(state.range(0)));
  run_rays(state, primary_rays(bench_camera(state.range(0), 512)), rs, false);
}
BENCHMARK(BM_PrimaryRays)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_MirrorRays(benchmark::State& state) {
  ThreadLimit limit(int(state.range(1)));
  const Scene& scene = bench_scene(state.range(0));
  RayScene rs(scene);
  run_rays(state, secondary_rays(scene, rs, primary_rays(bench_camera(state.range(0), 512)), false), rs,
           false);
}
BENCHMARK(BM_MirrorRays)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ShadowRays(benchmark::State& state) {
  ThreadLimit limit(int(state.range(1)));
  const Scene& scene = bench_scene(state.range(0));
  RayScene rs(scene);
  run_rays(state, secondary_rays(scene, rs, primary_rays(bench_camera(state.range(0), 512)), true), rs, true);
}
BENCHMARK(BM_ShadowRays)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

// Whole reference render, 256², default options (1 spp, 16 glossy rays, 2 bounces).
void BM_ReferenceRender(benchmark::State& state) {
  ThreadLimit limit(int(state.range(1)));
  const Scene& scene = bench_scene(state.range(0));
  RayScene rs(scene);
  Camera cam = bench_camera(state.range(0), 256);
  for (auto _ : state) benchmark::DoNotOptimize(render_reference(scene, rs, cam, ReferenceOptions{}));
  state.SetItemsProcessed(int64_t(state.iterations()) * cam.width * cam.height);
}
BENCHMARK(BM_ReferenceRender)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace proxima
