// Procedural mesh generators. All are deterministic, centered at the origin unless stated,
// with outward-facing counter-clockwise triangles, unit vertex normals and uvs.
#pragma once

#include "proxima/scene/mesh.h"

namespace proxima {

// UV sphere: `segments` around Y, `rings` from pole to pole. 2·segments·(rings−1) triangles.
Mesh make_sphere(float radius, int segments, int rings);

// Cylinder along +Y from y = 0 to y = height; `segments` around, `rings` bands along
// the side; optional caps. Side: 2·segments·rings triangles; each cap: segments.
Mesh make_cylinder(float radius, float height, int segments, int rings, bool capped);

// Torus around Y: major radius R, minor radius r. 2·major_segments·minor_segments triangles.
Mesh make_torus(float major_radius, float minor_radius, int major_segments, int minor_segments);

// Superellipsoid Σ|x_i / r_i|^(2/e) = 1 with semi-axes `radii`: the UV sphere's vertices
// n mapped to r_i·sign(n_i)·|n_i|^e, with the analytic normals. e = 1 is an ellipsoid,
// e → 0 a box with ever sharper rounded edges. 2·segments·(rings−1) triangles.
Mesh make_superellipsoid(vec3 radii, float exponent, int segments, int rings);

// Axis-aligned box centered at the origin with the given full size; faces outward,
// each face split into subdivisions² quads.
Mesh make_box(vec3 size, int subdivisions = 1);

// Rectangle in the XZ plane centered at the origin, normal +Y, subdivided into n × m quads.
Mesh make_plane(float size_x, float size_z, int n = 1, int m = 1);

// The Utah teapot from Newell's 32 bicubic Bézier patches, each tessellated into
// `tessellation`² quads (2 triangles each; the 8 patches whose first row is a pole — lid
// knob and bottom — give one triangle per pole quad): 64·n² − 8·n triangles. Resting on
// y = 0 and scaled to height 1, axis along +Y through x = z = 0, spout toward +X. Not
// closed (the lid sits in the opening with a gap; handle and spout pierce the body).
Mesh make_teapot(int tessellation);

}  // namespace proxima
