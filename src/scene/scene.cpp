#include "proxima/scene/scene.h"

#include <cmath>
#include <string>

#include "proxima/core/error.h"

namespace proxima {

uint32_t add_material(Scene& scene, const Material& material) {
  scene.materials.push_back(material);
  return uint32_t(scene.materials.size() - 1);
}

uint32_t add_object(Scene& scene, const Mesh& mesh, const std::string& name, uint32_t material,
                    const RigidAnimation& animation) {
  Object obj;
  obj.name = name;
  obj.first_triangle = uint32_t(scene.triangles.size());
  obj.triangle_count = uint32_t(mesh.triangles.size());
  obj.first_vertex = uint32_t(scene.positions.size());
  obj.vertex_count = uint32_t(mesh.positions.size());
  obj.animation = animation;
  uint32_t id = uint32_t(scene.objects.size());

  Mesh m = mesh;
  if (m.normals.size() != m.positions.size()) compute_vertex_normals(m);
  if (m.uvs.size() != m.positions.size()) m.uvs.assign(m.positions.size(), vec2(0.0f));
  scene.positions.insert(scene.positions.end(), m.positions.begin(), m.positions.end());
  scene.normals.insert(scene.normals.end(), m.normals.begin(), m.normals.end());
  scene.uvs.insert(scene.uvs.end(), m.uvs.begin(), m.uvs.end());
  for (const uvec3& t : m.triangles) scene.triangles.push_back(t + uvec3(obj.first_vertex));
  scene.triangle_material.insert(scene.triangle_material.end(), m.triangles.size(), material);
  scene.triangle_object.insert(scene.triangle_object.end(), m.triangles.size(), id);
  scene.objects.push_back(std::move(obj));
  return id;
}

// Non-finite vertices (possible in scenes built through the API; load refuses them) are
// left out: one NaN would make every bound, and the epsilons derived from the scene size,
// NaN, and the shadow rays with them (DegenerateGeometry.RasterTraceAndRenderAtEveryScale).
Bounds3 scene_bounds(const Scene& scene) {
  Bounds3 b;
  for (const vec3& p : scene.positions)
    if (is_finite(p)) b.extend(p);
  return b;
}

Bounds3 object_bounds(const Scene& scene, uint32_t object) {
  const Object& o = scene.objects[object];
  Bounds3 b;
  for (uint32_t i = 0; i < o.vertex_count; ++i)
    if (is_finite(scene.positions[o.first_vertex + i])) b.extend(scene.positions[o.first_vertex + i]);
  return b;
}

vec3 triangle_normal(const Scene& scene, uint32_t triangle) {
  const uvec3& t = scene.triangles[triangle];
  vec3 a = scene.positions[t.x], b = scene.positions[t.y], c = scene.positions[t.z];
  return glm::normalize(glm::cross(b - a, c - a));
}

vec3 triangle_point(const Scene& scene, uint32_t triangle, float u, float v) {
  const uvec3& t = scene.triangles[triangle];
  return barycentric(scene.positions[t.x], scene.positions[t.y], scene.positions[t.z], u, v);
}

vec3 shading_normal(const Scene& scene, uint32_t triangle, float u, float v) {
  const uvec3& t = scene.triangles[triangle];
  const vec3 n = barycentric(scene.normals[t.x], scene.normals[t.y], scene.normals[t.z], u, v);
  const float len = glm::length(n);
  return len > 0.0f ? n / len : triangle_normal(scene, triangle);
}

vec2 triangle_uv(const Scene& scene, uint32_t triangle, float u, float v) {
  const uvec3& t = scene.triangles[triangle];
  return barycentric(scene.uvs[t.x], scene.uvs[t.y], scene.uvs[t.z], u, v);
}

vec3 surface_diffuse(const Scene& scene, uint32_t triangle, float u, float v) {
  const Material& m = scene.materials[scene.triangle_material[triangle]];
  if (m.diffuse_texture < 0) return m.diffuse;
  return m.diffuse * sample_texture(scene.textures[size_t(m.diffuse_texture)], triangle_uv(scene, triangle, u, v));
}

bool has_animation(const Scene& scene) {
  for (const Object& o : scene.objects)
    if (o.animation.animated()) return true;
  return false;
}

Scene pose_scene(const Scene& rest, float t) {
  Scene posed = rest;
  for (const Object& o : rest.objects) {
    if (!o.animation.animated()) continue;
    mat4 m = animation_transform(o.animation, t);
    mat3 r(m);  // rigid: the rotation part transforms normals too
    for (uint32_t i = o.first_vertex; i < o.first_vertex + o.vertex_count; ++i) {
      posed.positions[i] = vec3(m * vec4(rest.positions[i], 1.0f));
      posed.normals[i] = glm::normalize(r * rest.normals[i]);
    }
  }
  return posed;
}

void sanitize_scene(Scene& scene, const std::string& source) {
  size_t nv = scene.positions.size();
  for (size_t i = 0; i < nv; ++i)
    if (!is_finite(scene.positions[i]))
      fail_input(source + ": vertex " + std::to_string(i) + " has a non-finite coordinate (NaN or Inf)");
  if (scene.triangle_material.size() != scene.triangles.size() ||
      scene.triangle_object.size() != scene.triangles.size())
    fail_input(source + ": per-triangle material/object arrays do not match the triangle count");
  if (scene.materials.empty()) fail_input(source + ": scene has no materials");
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const uvec3& t = scene.triangles[i];
    if (t.x >= nv || t.y >= nv || t.z >= nv)
      fail_input(source + ": triangle " + std::to_string(i) + " references a vertex out of range");
    if (scene.triangle_material[i] >= scene.materials.size())
      fail_input(source + ": triangle " + std::to_string(i) + " has an unknown material id");
    if (scene.triangle_object[i] >= scene.objects.size())
      fail_input(source + ": triangle " + std::to_string(i) + " has an unknown object id");
  }
  for (const Material& m : scene.materials) {
    if (!(m.specular >= 0.0f && m.specular <= 1.0f) || !(m.gloss >= 0.0f && m.gloss <= 1.0f))
      fail_input(source + ": material '" + m.name + "' has specular or gloss outside [0, 1]");
    if (m.diffuse_texture >= int(scene.textures.size()))
      fail_input(source + ": material '" + m.name + "' references a missing texture");
  }

  // Fill missing per-vertex attributes.
  if (scene.normals.size() != nv) {
    Mesh tmp;
    tmp.positions = scene.positions;
    tmp.triangles = scene.triangles;
    compute_vertex_normals(tmp);
    scene.normals = std::move(tmp.normals);
  }
  for (vec3& n : scene.normals)
    if (!is_finite(n) || glm::dot(n, n) == 0.0f) n = vec3(0.0f, 1.0f, 0.0f);
  if (scene.uvs.size() != nv) scene.uvs.assign(nv, vec2(0.0f));
  for (vec2& uv : scene.uvs)
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = vec2(0.0f);

  // Drop zero-area triangles (the cross product underflows or vanishes), keeping each
  // object's triangles contiguous and in order.
  std::vector<uvec3> tris;
  std::vector<uint32_t> mats, objs;
  tris.reserve(scene.triangles.size());
  std::vector<uint32_t> kept_per_object(scene.objects.size(), 0);
  uint32_t dropped = 0;
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const uvec3& t = scene.triangles[i];
    vec3 a = scene.positions[t.x], b = scene.positions[t.y], c = scene.positions[t.z];
    vec3 n = glm::cross(b - a, c - a);
    if (!(glm::dot(n, n) > 0.0f) || !is_finite(n)) {
      ++dropped;
      continue;
    }
    tris.push_back(t);
    mats.push_back(scene.triangle_material[i]);
    objs.push_back(scene.triangle_object[i]);
    ++kept_per_object[scene.triangle_object[i]];
  }
  if (dropped > 0) {
    uint32_t first = 0;
    for (size_t o = 0; o < scene.objects.size(); ++o) {
      scene.objects[o].first_triangle = first;
      scene.objects[o].triangle_count = kept_per_object[o];
      first += kept_per_object[o];
    }
    scene.triangles = std::move(tris);
    scene.triangle_material = std::move(mats);
    scene.triangle_object = std::move(objs);
  }
  scene.dropped_degenerate += dropped;
  if (scene.triangles.empty()) fail_input(source + ": scene has no (non-degenerate) triangles");
}

}  // namespace proxima
