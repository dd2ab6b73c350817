// Input polygons for the visibility module: greedy coplanar merge of edge-adjacent
// triangles into convex polygons (the "input polygons" of Funkhouser's spatial
// subdivision, section 3).
#include "proxima/visibility/polygons.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace proxima::visibility {
namespace {

// Welds positions closer than `tol` (greedily, in index order: a position joins the first
// earlier representative within `tol`, found in a hash grid of `tol`-sized cells).
std::vector<uint32_t> weld_positions(const std::vector<vec3>& in, double tol, std::vector<dvec3>& pos) {
  std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
  auto cell = [&](double x) { return int64_t(std::floor(x / tol)); };
  auto key = [](int64_t x, int64_t y, int64_t z) {
    return (uint64_t(x) * 73856093u) ^ (uint64_t(y) * 19349663u) ^ (uint64_t(z) * 83492791u);
  };
  std::vector<uint32_t> vid(in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    const dvec3 p(in[i]);
    const int64_t cx = cell(p.x), cy = cell(p.y), cz = cell(p.z);
    uint32_t found = kNone;
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(key(cx + dx, cy + dy, cz + dz));
          if (it == grid.end()) continue;
          for (uint32_t r : it->second)
            if (glm::length(pos[r] - p) <= tol && (found == kNone || r < found)) found = r;
        }
    if (found == kNone) {
      found = uint32_t(pos.size());
      pos.push_back(p);
      grid[key(cx, cy, cz)].push_back(found);
    }
    vid[i] = found;
  }
  return vid;
}

uint64_t edge_key(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; }

// True when the loop turns left (or goes straight) at every vertex about `normal`.
bool is_convex(const std::vector<dvec3>& pts, const dvec3& normal, double eps_area) {
  const size_t n = pts.size();
  for (size_t i = 0; i < n; ++i) {
    const dvec3& a = pts[(i + n - 1) % n];
    const dvec3& b = pts[i];
    const dvec3& c = pts[(i + 1) % n];
    if (glm::dot(glm::cross(b - a, c - b), normal) < -eps_area) return false;
  }
  return true;
}

}  // namespace

dvec3 newell_normal(const std::vector<dvec3>& loop) {
  dvec3 n(0.0);
  for (size_t i = 0; i < loop.size(); ++i) n += glm::cross(loop[i], loop[(i + 1) % loop.size()]);
  return n;
}

ModelPolygons extract_polygons(const Scene& scene) {
  ModelPolygons out;
  Bounds3 b = scene_bounds(scene);
  out.scale = std::max(1e-9, double(b.diagonal()));
  const double snap = kSnapTolerance * out.scale;
  const double eps_area = 1e-12 * out.scale * out.scale;
  out.triangle_polygon.assign(scene.triangles.size(), kNone);

  // Welded vertex ids: positions within the weld tolerance are one vertex (unwelded seams).
  std::vector<dvec3> pos;
  const std::vector<uint32_t> vid = weld_positions(scene.positions, kSnapTolerance * out.scale, pos);
  out.welded_positions.reserve(vid.size());
  for (uint32_t v : vid) out.welded_positions.push_back(vec3(pos[v]));

  for (uint32_t obj = 0; obj < scene.objects.size(); ++obj) {
    const Object& o = scene.objects[obj];
    // Directed edge (a, b) → triangle, within this object.
    std::unordered_map<uint64_t, uint32_t> directed;
    for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
      const uvec3& tri = scene.triangles[t];
      for (int k = 0; k < 3; ++k) directed[edge_key(vid[tri[k]], vid[tri[(k + 1) % 3]])] = t;
    }
    auto third = [&](uint32_t t, uint32_t a, uint32_t bb) {
      const uvec3& tri = scene.triangles[t];
      for (int k = 0; k < 3; ++k)
        if (vid[tri[k]] != a && vid[tri[k]] != bb) return vid[tri[k]];
      return kNone;
    };
    for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
      if (out.triangle_polygon[t] != kNone) continue;
      const uvec3& tri = scene.triangles[t];
      std::vector<uint32_t> loop = {vid[tri[0]], vid[tri[1]], vid[tri[2]]};
      std::vector<dvec3> pts = {pos[loop[0]], pos[loop[1]], pos[loop[2]]};
      dvec3 n = newell_normal(pts);
      if (glm::length(n) <= eps_area) continue;  // degenerate after welding: left out
      n = glm::normalize(n);
      const uint32_t id = uint32_t(out.polygons.size());
      InputPolygon poly;
      poly.object = obj;
      poly.triangles.push_back(t);
      out.triangle_polygon[t] = id;
      // Grow across edges while the merged loop stays planar and convex.
      bool grew = true;
      while (grew) {
        grew = false;
        for (size_t i = 0; i < loop.size() && !grew; ++i) {
          uint32_t a = loop[i], c = loop[(i + 1) % loop.size()];
          auto it = directed.find(edge_key(c, a));
          if (it == directed.end() || out.triangle_polygon[it->second] != kNone) continue;
          uint32_t u = it->second;
          uint32_t x = third(u, a, c);
          if (x == kNone || std::find(loop.begin(), loop.end(), x) != loop.end()) continue;
          // Within the snap tolerance of the plane (welding moves vertices that far).
          if (std::abs(glm::dot(n, pos[x] - pts[0])) > snap) continue;
          dvec3 nu = newell_normal({pos[c], pos[a], pos[x]});  // the neighbor's winding
          if (glm::length(nu) <= eps_area || glm::dot(glm::normalize(nu), n) < 0.0) continue;
          std::vector<uint32_t> cand = loop;
          cand.insert(cand.begin() + long(i) + 1, x);
          std::vector<dvec3> cpts;
          for (uint32_t v : cand) cpts.push_back(pos[v]);
          if (!is_convex(cpts, n, eps_area)) continue;
          loop = std::move(cand);
          pts = std::move(cpts);
          poly.triangles.push_back(u);
          out.triangle_polygon[u] = id;
          grew = true;
        }
      }
      // Drop collinear vertices (turn area below the tolerance).
      std::vector<dvec3> clean;
      for (size_t i = 0; i < pts.size(); ++i) {
        const dvec3& p = pts[(i + pts.size() - 1) % pts.size()];
        const dvec3& q = pts[(i + 1) % pts.size()];
        if (glm::length(glm::cross(pts[i] - p, q - pts[i])) > eps_area) clean.push_back(pts[i]);
      }
      poly.vertices = clean.size() >= 3 ? clean : pts;
      poly.plane.normal = glm::normalize(newell_normal(poly.vertices));
      dvec3 centroid(0.0);
      for (const dvec3& p : poly.vertices) centroid += p;
      centroid /= double(poly.vertices.size());
      poly.plane.offset = -glm::dot(poly.plane.normal, centroid);
      out.polygons.push_back(std::move(poly));
    }
  }
  return out;
}

Scene welded_scene(const Scene& scene, const ModelPolygons& model) {
  Scene out = scene;
  out.positions = model.welded_positions;
  return out;
}

}  // namespace proxima::visibility
