#include "proxima/trace/object_bvh.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace proxima {

namespace {

constexpr uint32_t kLeafTriangles = 4;

// Entry and exit parameters of the ray in box b; empty when t_exit < t_entry.
bool slab(const Bounds3& b, vec3 origin, vec3 inv_dir, float t_min, float t_max, float& t_entry) {
  for (int a = 0; a < 3; ++a) {
    float ta = (b.min[a] - origin[a]) * inv_dir[a], tb = (b.max[a] - origin[a]) * inv_dir[a];
    if (ta > tb) std::swap(ta, tb);
    // NaN (0·∞ on a slab boundary) keeps the interval: conservative.
    if (ta > t_min) t_min = ta;
    if (tb < t_max) t_max = tb;
  }
  t_entry = t_min;
  return t_min <= t_max;
}

}  // namespace

ObjectBvh::ObjectBvh(const Scene& scene, uint32_t object) {
  const Object& obj = scene.objects[object];
  if (obj.triangle_count == 0) return;
  std::vector<uint32_t> order(obj.triangle_count);
  std::iota(order.begin(), order.end(), obj.first_triangle);
  std::vector<vec3> centroid(obj.triangle_count);
  std::vector<Bounds3> box(obj.triangle_count);
  for (uint32_t k = 0; k < obj.triangle_count; ++k) {
    const uvec3& t = scene.triangles[obj.first_triangle + k];
    for (uint32_t v : {t.x, t.y, t.z}) box[k].extend(scene.positions[v]);
    centroid[k] = box[k].center();
  }
  auto local = [&](uint32_t tri) { return tri - obj.first_triangle; };
  nodes_.reserve(2 * obj.triangle_count / kLeafTriangles + 1);
  nodes_.push_back({});
  // Top-down median split on the centroids' longest axis (ties by triangle id: the same
  // tree on every run).
  struct Task {
    uint32_t node, begin, end;
  };
  std::vector<Task> stack{{0, 0, obj.triangle_count}};
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    Bounds3 b, cb;
    for (uint32_t k = task.begin; k < task.end; ++k) {
      b.extend(box[local(order[k])]);
      cb.extend(centroid[local(order[k])]);
    }
    nodes_[task.node].box = b;
    const uint32_t n = task.end - task.begin;
    const vec3 ext = cb.extent();
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
    if (n <= kLeafTriangles || !(ext[axis] > 0.0f)) {
      nodes_[task.node].first = task.begin;
      nodes_[task.node].count = n;
      continue;
    }
    const uint32_t mid = task.begin + n / 2;
    std::nth_element(order.begin() + task.begin, order.begin() + mid, order.begin() + task.end,
                     [&](uint32_t p, uint32_t q) {
                       const float cp = centroid[local(p)][axis], cq = centroid[local(q)][axis];
                       return cp < cq || (cp == cq && p < q);
                     });
    const uint32_t left = uint32_t(nodes_.size());
    nodes_.push_back({});
    nodes_.push_back({});
    nodes_[task.node].first = left;
    nodes_[task.node].count = 0;
    stack.push_back({left + 1, mid, task.end});
    stack.push_back({left, task.begin, mid});
  }
  triangle_ = order;
  a_.resize(order.size());
  e1_.resize(order.size());
  e2_.resize(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    const uvec3& t = scene.triangles[order[k]];
    a_[k] = scene.positions[t.x];
    e1_[k] = scene.positions[t.y] - a_[k];
    e2_[k] = scene.positions[t.z] - a_[k];
  }
}

std::optional<ObjectHit> ObjectBvh::intersect(vec3 origin, vec3 dir, float t_min, float t_max) const {
  if (nodes_.empty() || !(t_min < t_max)) return std::nullopt;
  const vec3 inv_dir = 1.0f / dir;
  ObjectHit best;
  best.t = t_max;
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    float entry = 0.0f;
    if (!slab(node.box, origin, inv_dir, t_min, best.t, entry)) continue;
    if (node.count == 0) {
      // Nearer child last, so it is visited first.
      float e0 = kInf, e1 = kInf;
      const bool h0 = slab(nodes_[node.first].box, origin, inv_dir, t_min, best.t, e0);
      const bool h1 = slab(nodes_[node.first + 1].box, origin, inv_dir, t_min, best.t, e1);
      if (h0 && h1) {
        const bool left_first = e0 <= e1;
        stack[top++] = left_first ? node.first + 1 : node.first;
        stack[top++] = left_first ? node.first : node.first + 1;
      } else if (h0) {
        stack[top++] = node.first;
      } else if (h1) {
        stack[top++] = node.first + 1;
      }
      continue;
    }
    for (uint32_t k = node.first; k < node.first + node.count; ++k) {
      // Möller–Trumbore, both faces.
      const vec3 p = glm::cross(dir, e2_[k]);
      const float det = glm::dot(e1_[k], p);
      if (det == 0.0f) continue;
      const float inv = 1.0f / det;
      const vec3 s = origin - a_[k];
      const float u = glm::dot(s, p) * inv;
      if (u < 0.0f || u > 1.0f) continue;
      const vec3 q = glm::cross(s, e1_[k]);
      const float v = glm::dot(dir, q) * inv;
      if (v < 0.0f || u + v > 1.0f) continue;
      const float t = glm::dot(e2_[k], q) * inv;
      if (t > t_min && (t < best.t || (t == best.t && triangle_[k] < best.triangle))) {
        best = ObjectHit{t, triangle_[k], u, v};
      }
    }
  }
  if (best.triangle == kNoTriangle) return std::nullopt;
  return best;
}

}  // namespace proxima
