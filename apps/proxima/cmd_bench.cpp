// `proxima bench trace`: BVH build time and rays per second of the Embree reference on a
// built-in scene, at 1 thread and at all threads, medians over repetitions.
#include <cstdio>
#include <memory>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/scene/load.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::cli {

namespace {

struct BenchFlags {
  CommonOptions common;
  CameraChoice camera;
  int reps = 5;
};

std::vector<Ray> primary_rays(const Camera& cam) {
  std::vector<Ray> rays(size_t(cam.width) * size_t(cam.height));
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      rays[size_t(y) * size_t(cam.width) + size_t(x)] = ray_through(cam, {float(x) + 0.5f, float(y) + 0.5f});
  return rays;
}

// Mirror rays from every primary hit on a reflective surface (what reflections cost).
std::vector<Ray> reflection_rays(const Scene& scene, std::span<const Ray> primary, std::span<const Hit> hits) {
  float eps = 1e-4f * std::max(1.0f, scene_bounds(scene).diagonal());
  std::vector<Ray> rays;
  for (size_t i = 0; i < hits.size(); ++i) {
    const Hit& h = hits[i];
    if (!h.valid() || !scene.materials[scene.triangle_material[h.triangle]].reflective()) continue;
    vec3 n = shading_normal(scene, h.triangle, h.u, h.v);
    if (glm::dot(n, primary[i].dir) > 0.0f) n = -n;
    Ray r;
    r.origin = primary[i].origin + h.t * primary[i].dir;
    r.dir = glm::reflect(primary[i].dir, n);
    r.tmin = eps;
    rays.push_back(r);
  }
  return rays;
}

// Median rays per second (millions) of batched closest-hit queries.
double median_mrays(const RayScene& rs, std::span<const Ray> rays, int reps) {
  std::vector<Hit> hits(rays.size());
  rs.intersect(rays, hits);  // warm-up
  std::vector<double> ms;
  for (int i = 0; i < reps; ++i) {
    Stopwatch w;
    rs.intersect(rays, hits);
    ms.push_back(w.elapsed_ms());
  }
  return double(rays.size()) / (median(ms) * 1e3);
}

int run_trace(const BenchFlags& f) {
  if (f.reps < 1 || f.reps > 1000) fail_input("--reps: must be in 1..1000");
  Scene scene = load_scene(f.common.scene);
  Camera cam = pick_camera(scene, f.camera, f.common.width, f.common.height);
  auto out = prepare_out_dir(f.common.out);
  int all = f.common.threads > 0 ? f.common.threads : hardware_threads();

  Results results;
  results.command = command_line();
  results.threads = all;
  std::vector<Ray> primary = primary_rays(cam);
  std::vector<Hit> hits(primary.size());
  std::vector<Ray> reflected;
  Table table{"bench trace: " + scene.name + ", " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                  ", median of " + std::to_string(f.reps),
              {"threads", "bvh_build_ms", "primary_mrays_s", "reflection_mrays_s"},
              {}};
  for (int threads : {1, all}) {
    ThreadLimit limit(threads);
    std::vector<double> build;
    std::unique_ptr<RayScene> rs;
    for (int i = 0; i < f.reps; ++i) {
      rs = std::make_unique<RayScene>(scene);
      build.push_back(rs->build_ms());
    }
    if (reflected.empty()) {
      rs->intersect(primary, hits);
      reflected = reflection_rays(scene, primary, hits);
    }
    double p = median_mrays(*rs, primary, f.reps);
    double r = reflected.empty() ? 0.0 : median_mrays(*rs, reflected, f.reps);
    std::string suffix = threads == all ? "" : "_1t";
    results.metrics["bvh_build_ms" + suffix] = median(build);
    results.metrics["primary_mrays_s" + suffix] = p;
    results.metrics["reflection_mrays_s" + suffix] = r;
    table.rows.push_back({double(threads), median(build), p, r});
    if (threads == all) break;  // all == 1 on a single-core machine
  }
  results.metrics["reflection_rays"] = double(reflected.size());
  results.metrics["triangles"] = double(scene.triangles.size());
  results.tables.push_back(table);
  publish_results(out, results);
  return 0;
}

}  // namespace

Command register_bench(CLI::App& root) {
  static BenchFlags f;
  auto* app = root.add_subcommand("bench", "benchmarks (medians of repetitions, written to results.json)");
  app->require_subcommand(1);
  auto* trace = app->add_subcommand("trace", "Embree reference: BVH build, primary and reflection rays per second");
  add_scene_flag(trace, f.common, "living-room");
  add_camera_flags(trace, f.camera);
  f.common.width = 1024;
  f.common.height = 1024;
  add_size_flags(trace, f.common);
  add_threads_flag(trace, f.common);
  add_out_flag(trace, f.common, false);
  f.common.out = "out/bench-trace";
  trace->add_option("--reps", f.reps, "repetitions per measurement")->capture_default_str();
  return {app, [trace] {
            if (trace->parsed()) return run_trace(f);
            return 2;
          }};
}

}  // namespace proxima::cli
