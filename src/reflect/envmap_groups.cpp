#include "proxima/reflect/envmap_groups.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
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
// (sorted); kInf where the ray escapes. Surfaces of `skip` are passed through, each with a
// step of 1e-5 × max(`scale`, t) beyond it.
float distance_past(const Scene& scene, const RayScene& rays, vec3 origin, vec3 dir,
                    std::span<const uint32_t> skip, float scale) {
  Ray ray{origin, dir, 0.0f, kInf};
  for (int pass = 0; pass < 256; ++pass) {
    const Hit h = rays.intersect(ray);
    if (!h.valid()) return kInf;
    if (!std::binary_search(skip.begin(), skip.end(), scene.triangle_object[h.triangle])) return h.t;
    ray.tmin = h.t + 1e-5f * std::max(scale, h.t);
  }
  return ray.tmin;  // a pile of the group's own surfaces: take the depth reached
}

// Mean over the probe directions of min(1, radius / d) from `center`; stops early, with a
// value above `stop`, once the mean can no longer come out at or below `stop`.
float group_parallax(const Scene& scene, const RayScene& rays, vec3 center, float radius,
                     std::span<const uint32_t> reflectors, float stop = kInf) {
  if (radius <= 0.0f) return 0.0f;
  const double limit = double(stop) * double(kGroupProbeDirections);
  double sum = 0.0;
  for (const vec3& dir : probe_directions()) {
    const float d = distance_past(scene, rays, center, dir, reflectors, radius);
    sum += d > radius ? double(radius / d) : 1.0;
    if (sum > limit) return std::nextafter(stop, kInf);
  }
  return float(sum / double(kGroupProbeDirections));
}

// A candidate merge: its center, and a radius from the objects' bounding boxes (≥ the
// vertices' radius; cheap for groups of large meshes).
struct Candidate {
  std::vector<uint32_t> reflectors;
  vec3 center{0.0f};
  float radius = 0.0f;
};

Candidate candidate(const EnvmapGroup& a, const EnvmapGroup& b, std::span<const Bounds3> bounds) {
  Candidate c;
  std::merge(a.reflectors.begin(), a.reflectors.end(), b.reflectors.begin(), b.reflectors.end(),
             std::back_inserter(c.reflectors));
  Bounds3 all;
  for (uint32_t o : c.reflectors) all.extend(bounds[o]);
  c.center = all.center();
  for (uint32_t o : c.reflectors) c.radius = std::max(c.radius, bounds[o].farthest_corner_distance(c.center));
  return c;
}

// The pair (i < j) with the smallest cost; ties to the smallest i, then j.
std::pair<size_t, size_t> cheapest(const std::vector<std::vector<float>>& cost) {
  size_t bi = 0, bj = 1;
  for (size_t i = 0; i < cost.size(); ++i)
    for (size_t j = i + 1; j < cost.size(); ++j)
      if (cost[i][j] < cost[bi][bj]) bi = i, bj = j;
  return {bi, bj};
}

// Merges groups i < j into i, and drops j's row and column of `cost`.
void merge_into(const Scene& scene, const RayScene& rays, std::vector<EnvmapGroup>& groups,
                std::vector<std::vector<float>>& cost, size_t i, size_t j) {
  std::vector<uint32_t> both;
  std::merge(groups[i].reflectors.begin(), groups[i].reflectors.end(), groups[j].reflectors.begin(),
             groups[j].reflectors.end(), std::back_inserter(both));
  groups[i] = make_envmap_group(scene, rays, std::move(both));
  groups.erase(groups.begin() + std::ptrdiff_t(j));
  cost.erase(cost.begin() + std::ptrdiff_t(j));
  for (auto& row : cost) row.erase(row.begin() + std::ptrdiff_t(j));
}

}  // namespace

void validate(const EnvmapGroupOptions& o) {
  require_in_range(o.max_groups, 1, kMaxEnvmapGroups, "--max-maps");
  if (!(o.max_parallax >= 0.0f) || !std::isfinite(o.max_parallax))
    fail_input("--group-parallax: must be a number ≥ 0");
}

EnvmapGroup make_envmap_group(const Scene& scene, const RayScene& rays, std::vector<uint32_t> reflectors) {
  std::sort(reflectors.begin(), reflectors.end());
  EnvmapGroup g;
  g.reflectors = std::move(reflectors);
  g.center = projection_center(scene, g.reflectors);
  g.radius = viewer_radius(scene, g.reflectors, g.center);
  g.parallax = group_parallax(scene, rays, g.center, g.radius, g.reflectors);
  return g;
}

std::vector<EnvmapGroup> group_reflectors(const Scene& scene, const RayScene& rays,
                                          std::span<const uint32_t> reflectors, const EnvmapGroupOptions& o) {
  validate(o);
  std::vector<EnvmapGroup> groups(reflectors.size());
  parallel_for(groups.size(), 1, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) groups[i] = make_envmap_group(scene, rays, {reflectors[i]});
  });
  std::vector<Bounds3> bounds(scene.objects.size());
  for (uint32_t r : reflectors) bounds[r] = object_bounds(scene, r);
  // Valid merges first: cost[i][j] (i < j) is the parallax of groups i and j merged, or a
  // value above max_parallax once it is known to exceed it.
  std::vector<std::vector<float>> cost(groups.size(), std::vector<float>(groups.size(), kInf));
  auto parallax_row = [&](size_t i) {
    parallel_for(groups.size(), 1, [&](size_t b, size_t e) {
      for (size_t j = b; j < e; ++j) {
        if (j == i) continue;
        const Candidate c = candidate(groups[i], groups[j], bounds);
        cost[std::min(i, j)][std::max(i, j)] =
            group_parallax(scene, rays, c.center, c.radius, c.reflectors, o.max_parallax);
      }
    });
  };
  for (size_t i = 0; i < groups.size(); ++i) parallax_row(i);
  while (groups.size() > 1) {
    const auto [i, j] = cheapest(cost);
    if (!(cost[i][j] <= o.max_parallax)) break;
    merge_into(scene, rays, groups, cost, i, j);
    parallax_row(i);
  }
  // Then, beyond max_groups, the most compact merges (smallest merged radius): the parallax
  // saturates for groups inside or against their surroundings (furniture on a floor), the
  // radius still tells reflectors close together from ones far apart.
  auto radius_row = [&](size_t i) {
    for (size_t j = 0; j < groups.size(); ++j)
      if (j != i) cost[std::min(i, j)][std::max(i, j)] = candidate(groups[i], groups[j], bounds).radius;
  };
  if (groups.size() > size_t(o.max_groups))
    for (size_t i = 0; i < groups.size(); ++i) radius_row(i);
  while (groups.size() > size_t(o.max_groups)) {
    const auto [i, j] = cheapest(cost);
    merge_into(scene, rays, groups, cost, i, j);
    radius_row(i);
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
