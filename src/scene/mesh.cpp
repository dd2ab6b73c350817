#include "proxima/scene/mesh.h"

namespace proxima {

void transform_mesh(Mesh& mesh, const mat4& transform) {
  mat3 normal_matrix = glm::transpose(glm::inverse(mat3(transform)));
  for (vec3& p : mesh.positions) p = vec3(transform * vec4(p, 1.0f));
  for (vec3& n : mesh.normals) n = glm::normalize(normal_matrix * n);
  // A mirroring transform flips the winding; restore counter-clockwise fronts.
  if (glm::determinant(mat3(transform)) < 0.0f)
    for (uvec3& t : mesh.triangles) std::swap(t.y, t.z);
}

void compute_vertex_normals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), vec3(0.0f));
  for (const uvec3& t : mesh.triangles) {
    vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    vec3 n = glm::cross(b - a, c - a);  // length = 2·area: area weighting for free
    mesh.normals[t.x] += n;
    mesh.normals[t.y] += n;
    mesh.normals[t.z] += n;
  }
  for (vec3& n : mesh.normals) {
    float len = glm::length(n);
    n = len > 0.0f ? n / len : vec3(0.0f, 1.0f, 0.0f);
  }
}

void append_mesh(Mesh& a, const Mesh& b) {
  uint32_t base = uint32_t(a.positions.size());
  // Keep attribute arrays parallel to positions even if only one side has them.
  if (a.normals.size() != a.positions.size() || b.normals.size() != b.positions.size()) {
    if (a.normals.size() != a.positions.size()) compute_vertex_normals(a);
    Mesh copy = b;
    if (copy.normals.size() != copy.positions.size()) compute_vertex_normals(copy);
    a.normals.insert(a.normals.end(), copy.normals.begin(), copy.normals.end());
  } else {
    a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
  }
  a.uvs.resize(base, vec2(0.0f));
  if (b.uvs.size() == b.positions.size()) a.uvs.insert(a.uvs.end(), b.uvs.begin(), b.uvs.end());
  else a.uvs.resize(base + b.positions.size(), vec2(0.0f));
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (const uvec3& t : b.triangles) a.triangles.push_back(t + uvec3(base));
}

}  // namespace proxima
