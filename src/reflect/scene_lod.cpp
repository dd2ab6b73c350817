// Levels of detail by vertex clustering per object (scene_lod.h).
#include "proxima/reflect/scene_lod.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace proxima {

namespace {

// Triangle key up to rotation (the orientation is kept: a reversed triangle is another).
uint64_t rotation_key(uvec3 t) {
  while (t.x > t.y || t.x > t.z) t = uvec3(t.y, t.z, t.x);
  return (uint64_t(t.x) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(t.y) << 21) ^ (uint64_t(t.z) * 0xC2B2AE3D27D4EB4Full);
}

struct TriangleKey {
  uvec3 t;
  bool operator==(const TriangleKey& o) const {
    uvec3 a = t, b = o.t;
    while (a.x > a.y || a.x > a.z) a = uvec3(a.y, a.z, a.x);
    while (b.x > b.y || b.x > b.z) b = uvec3(b.y, b.z, b.x);
    return a == b;
  }
};
struct TriangleKeyHash {
  size_t operator()(const TriangleKey& k) const { return size_t(rotation_key(k.t)); }
};

}  // namespace

std::vector<float> lod_cells(float scene_diagonal, int levels) {
  std::vector<float> cells;
  for (int level = 1; level < levels; ++level) cells.push_back(scene_diagonal * std::ldexp(1.0f, level - 12));
  return cells;
}

SceneLod build_scene_lod(const Scene& rest, std::span<const float> cells) {
  SceneLod out;
  out.source_objects = uint32_t(rest.objects.size());
  out.cell.assign(cells.begin(), cells.end());
  const uint32_t n = out.source_objects;
  out.objects.resize(size_t(out.levels()) * n);
  std::vector<uint32_t> representative(rest.positions.size());
  std::vector<std::pair<uint64_t, uint32_t>> keyed;
  std::unordered_set<TriangleKey, TriangleKeyHash> seen;
  for (uint32_t level = 0; level < out.levels(); ++level) {
    for (uint32_t o = 0; o < n; ++o) {
      const Object& src = rest.objects[o];
      Object& dst = out.objects[out.object(level, o)];
      dst.name = src.name;
      dst.animation = src.animation;
      dst.first_triangle = uint32_t(out.triangles.size());
      // The object's vertex range, from its triangles.
      uint32_t lo = ~0u, hi = 0;
      for (uint32_t t = src.first_triangle; t < src.first_triangle + src.triangle_count; ++t)
        for (int k = 0; k < 3; ++k) {
          lo = std::min(lo, rest.triangles[t][k]);
          hi = std::max(hi, rest.triangles[t][k]);
        }
      if (src.triangle_count == 0) lo = hi = 0;
      dst.first_vertex = lo;
      dst.vertex_count = src.triangle_count == 0 ? 0 : hi - lo + 1;
      if (level > 0 && src.triangle_count > 0) {
        // Cells of the grid anchored at the object's lowest corner; the lowest vertex index
        // of a cell represents it (sorted by (cell, index)).
        const float cell = out.cell[level - 1];
        vec3 origin(kInf);
        for (uint32_t v = lo; v <= hi; ++v) origin = glm::min(origin, rest.positions[v]);
        keyed.clear();
        for (uint32_t v = lo; v <= hi; ++v) {
          const vec3 c = glm::floor((rest.positions[v] - origin) / cell);
          const uint64_t x = uint64_t(std::clamp(c.x, 0.0f, 2097151.0f)), y = uint64_t(std::clamp(c.y, 0.0f, 2097151.0f)),
                         z = uint64_t(std::clamp(c.z, 0.0f, 2097151.0f));
          keyed.emplace_back((x << 42) | (y << 21) | z, v);
        }
        std::sort(keyed.begin(), keyed.end());
        for (size_t i = 0; i < keyed.size(); ++i)
          representative[keyed[i].second] =
              i > 0 && keyed[i - 1].first == keyed[i].first ? representative[keyed[i - 1].second] : keyed[i].second;
      }
      seen.clear();
      for (uint32_t t = src.first_triangle; t < src.first_triangle + src.triangle_count; ++t) {
        uvec3 idx = rest.triangles[t];
        if (level > 0) {
          idx = uvec3(representative[idx.x], representative[idx.y], representative[idx.z]);
          if (idx.x == idx.y || idx.y == idx.z || idx.x == idx.z) continue;
          if (!seen.insert(TriangleKey{idx}).second) continue;
        }
        out.triangles.push_back(idx);
        out.triangle_object.push_back(out.object(level, o));
        out.source_triangle.push_back(t);
      }
      dst.triangle_count = uint32_t(out.triangles.size()) - dst.first_triangle;
    }
  }
  return out;
}

Scene lod_draw_scene(const SceneLod& lod, const Scene& posed) {
  Scene s;
  s.name = posed.name;
  s.positions = posed.positions;
  s.triangles = lod.triangles;
  s.triangle_object = lod.triangle_object;
  s.objects = lod.objects;
  return s;
}

}  // namespace proxima
