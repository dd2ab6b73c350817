#include "proxima/study/trace_bench.h"

#include <algorithm>
#include <memory>
#include <span>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
#include "proxima/core/timer.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::study {

namespace {

std::vector<Ray> primary_rays(const Camera& cam) {
  std::vector<Ray> rays(size_t(cam.width) * size_t(cam.height));
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      rays[size_t(y) * size_t(cam.width) + size_t(x)] = ray_through(cam, {float(x) + 0.5f, float(y) + 0.5f});
  return rays;
}

// Mirror rays from every primary hit on a reflective surface (what reflections cost).
std::vector<Ray> reflection_rays(const Scene& scene, std::span<const Ray> primary, std::span<const Hit> hits) {
  const float eps = 1e-4f * std::max(1.0f, scene_bounds(scene).diagonal());
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

}  // namespace

void validate(const TraceBenchOptions& o) {
  require_in_range(o.reps, 1, 1000, "--reps");
}

Results run_trace_bench(const Scene& scene, const TraceBenchOptions& options, const StudyOutput& /*out*/,
                        Progress* /*progress*/) {
  validate(options);
  const Camera cam = pick_camera(scene, options.camera, options.width, options.height);
  const int all = options.threads > 0 ? options.threads : hardware_threads();
  const int reps = options.reps;
  Results results;
  const std::vector<Ray> primary = primary_rays(cam);
  std::vector<Hit> hits(primary.size());
  std::vector<Ray> reflected;
  Table table{"bench trace: " + scene.name + ", " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                  ", median of " + std::to_string(reps),
              {"threads", "bvh_build_ms", "primary_mrays_s", "reflection_mrays_s"},
              {}};
  for (int threads : {1, all}) {
    ThreadLimit limit(threads);
    std::vector<double> build;
    std::unique_ptr<RayScene> rs;
    for (int i = 0; i < reps; ++i) {
      rs = std::make_unique<RayScene>(scene);
      build.push_back(rs->build_ms());
    }
    if (reflected.empty()) {
      rs->intersect(primary, hits);
      reflected = reflection_rays(scene, primary, hits);
    }
    const double p = median_mrays(*rs, primary, reps);
    const double r = reflected.empty() ? 0.0 : median_mrays(*rs, reflected, reps);
    const std::string suffix = threads == all ? "" : "_1t";
    results.metrics["bvh_build_ms" + suffix] = median(build);
    results.metrics["primary_mrays_s" + suffix] = p;
    results.metrics["reflection_mrays_s" + suffix] = r;
    table.rows.push_back({double(threads), median(build), p, r});
    if (threads == all) break;  // all == 1 on a single-core machine
  }
  results.metrics["reflection_rays"] = double(reflected.size());
  results.metrics["triangles"] = double(scene.triangles.size());
  results.tables.push_back(table);
  return results;
}

}  // namespace proxima::study
