// Mesh: an indexed triangle mesh, the unit procedural generators and importers produce
// before it is appended to a Scene as one object.
#pragma once

#include <vector>

#include "proxima/core/math.h"

namespace proxima {

struct Mesh {
  std::vector<vec3> positions;
  std::vector<vec3> normals;  // per vertex, unit; same size as positions (or empty: computed)
  std::vector<vec2> uvs;      // per vertex; same size as positions (or empty: zeros)
  std::vector<uvec3> triangles;  // counter-clockwise seen from the front (outside)
};

// Applies an affine transform to positions and (inverse-transpose) to normals.
void transform_mesh(Mesh& mesh, const mat4& transform);

// Area-weighted vertex normals from the triangles (for meshes without normals).
void compute_vertex_normals(Mesh& mesh);

// Appends b's vertices and triangles to a.
void append_mesh(Mesh& a, const Mesh& b);

}  // namespace proxima
