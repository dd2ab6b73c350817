#include "proxima/reflect/envmap_groups.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/reflect/envmap_reflection.h"

namespace proxima {
namespace {

// kGroupProbeDirections directions spread evenly over the sphere (a Fibonacci lattice).
const std::array<vec3, kGroupProbeDirections>& probe_directions() {
  static const std::array<vec3, kGroupProbeDirections> dirs = [] {
    std::array<vec3, kGroupProbeDirections> d{};
    const float golden = 3.14159265f * (3.0f - std::sqrt(5.0f));
    for (int i = 0; i < kGroupProbeDirections; ++i) {
      const float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(kGroupProbeDirections);
      const float r = std::sqrt(std::max(0.0f, 1.0f - y * y));
      d[size_t(i)] = vec3(r * std::cos(golden * float(i)), y, r * std::sin(golden * float(i)));
    }
    return d;
  }();
  return dirs;
}

// Distance from `origin` along `dir` to the first surface of an object not in `skip`
// (sorted); kInf where the ray escapes. Surfaces of `skip` are passed through.
float distance_past(const Scene& scene, const RayScene& rays, vec3 origin, vec3 dir,
                    std::span<const uint32_t> skip, float step) {
  Ray ray{origin, dir, 0.0f, kInf};
  for (int pass = 0; pass < 256; ++pass) {
    const Hit h = rays.intersect(ray);
    if (!h.valid()) return kInf;
    if (!std::binary_search(skip.begin(), skip.end(), scene.triangle_object[h.triangle])) return h.t;
    ray.tmin = h.t + step;
  }
  return ray.tmin;  // a pile of the group's own surfaces: take the depth reached
}

float group_parallax(const Scene& scene, const RayScene& rays, const EnvmapGroup& g) {
  if (g.radius <= 0.0f) return 0.0f;
  const float step = 1e-5f * std::max(scene_bounds(scene).diagonal(), 1e-6f);
  double sum = 0.0;
  for (const vec3& dir : probe_directions()) {
    const float d = distance_past(scene, rays, g.center, dir, g.reflectors, step);
    sum += d > g.radius ? double(g.radius / d) : 1.0;
  }
  return float(sum / double(kGroupProbeDirections));
}

std::vector<uint32_t> merged(const EnvmapGroup& a, const EnvmapGroup& b) {
  std::vector<uint32_t> out;
  std::merge(a.reflectors.begin(), a.reflectors.end(), b.reflectors.begin(), b.reflectors.end(),
             std::back_inserter(out));
  return out;
}

}  // namespace

EnvmapGroup make_envmap_group(const Scene& scene, const RayScene& rays, std::vector<uint32_t> reflectors) {
  std::sort(reflectors.begin(), reflectors.end());
  EnvmapGroup g;
  g.reflectors = std::move(reflectors);
  g.center = projection_center(scene, g.reflectors);
  g.radius = viewer_radius(scene, g.reflectors, g.center);
  g.parallax = group_parallax(scene, rays, g);
  return g;
}

std::vector<EnvmapGroup> group_reflectors(const Scene& scene, const RayScene& rays,
                                          std::span<const uint32_t> reflectors, const EnvmapGroupOptions& o) {
  if (o.max_groups < 1 || o.max_groups > kMaxEnvmapGroups)
    fail_input("--max-maps: must be in 1.." + std::to_string(kMaxEnvmapGroups));
  if (!(o.max_parallax >= 0.0f) || !std::isfinite(o.max_parallax))
    fail_input("--group-parallax: must be a number ≥ 0");
  std::vector<EnvmapGroup> groups(reflectors.size());
  parallel_for(groups.size(), 1, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) groups[i] = make_envmap_group(scene, rays, {reflectors[i]});
  });
  // cost[i][j], i < j: the parallax of groups i and j merged.
  std::vector<std::vector<float>> cost(groups.size(), std::vector<float>(groups.size(), 0.0f));
  auto fill_row = [&](size_t i) {
    parallel_for(groups.size(), 1, [&](size_t b, size_t e) {
      for (size_t j = b; j < e; ++j) {
        if (j == i) continue;
        const float c = make_envmap_group(scene, rays, merged(groups[i], groups[j])).parallax;
        cost[std::min(i, j)][std::max(i, j)] = c;
      }
    });
  };
  for (size_t i = 0; i < groups.size(); ++i) fill_row(i);
  while (groups.size() > 1) {
    size_t bi = 0, bj = 1;
    for (size_t i = 0; i < groups.size(); ++i)
      for (size_t j = i + 1; j < groups.size(); ++j)
        if (cost[i][j] < cost[bi][bj]) bi = i, bj = j;
    if (groups.size() <= size_t(o.max_groups) && !(cost[bi][bj] <= o.max_parallax)) break;
    groups[bi] = make_envmap_group(scene, rays, merged(groups[bi], groups[bj]));
    groups.erase(groups.begin() + std::ptrdiff_t(bj));
    cost.erase(cost.begin() + std::ptrdiff_t(bj));
    for (auto& row : cost) row.erase(row.begin() + std::ptrdiff_t(bj));
    fill_row(bi);
  }
  std::sort(groups.begin(), groups.end(),
            [](const EnvmapGroup& a, const EnvmapGroup& b) { return a.reflectors.front() < b.reflectors.front(); });
  return groups;
}

std::vector<uint32_t> envmap_group_of_objects(const Scene& scene, std::span<const EnvmapGroup> groups) {
  std::vector<uint32_t> out(scene.objects.size(), kNoEnvmapGroup);
  for (size_t g = 0; g < groups.size(); ++g)
    for (uint32_t o : groups[g].reflectors)
      if (o < out.size()) out[o] = uint32_t(g);
  return out;
}

}  // namespace proxima
