// Scene: a flattened, indexed triangle set with per-triangle material and object ids,
// plus materials, lights, environment, cameras and camera paths.
// Triangle ids (DESIGN.md) are indices into `triangles`; object ids index `objects`.
// Every object owns a contiguous range of triangles and of vertices.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/scene/animation.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/light.h"
#include "proxima/scene/material.h"
#include "proxima/scene/mesh.h"

namespace proxima {

struct Object {
  std::string name;
  uint32_t first_triangle = 0;
  uint32_t triangle_count = 0;
  uint32_t first_vertex = 0;
  uint32_t vertex_count = 0;
  RigidAnimation animation;  // rest pose = the stored positions
};

struct NamedCamera {
  std::string name;
  Camera camera;  // width/height here are defaults; commands override them
};

struct Scene {
  std::string name;

  // Geometry (rest pose). normals/uvs are per vertex, same size as positions.
  std::vector<vec3> positions;
  std::vector<vec3> normals;
  std::vector<vec2> uvs;
  std::vector<uvec3> triangles;           // vertex indices, counter-clockwise front
  std::vector<uint32_t> triangle_material;  // per triangle, index into materials
  std::vector<uint32_t> triangle_object;    // per triangle, index into objects

  std::vector<Object> objects;
  std::vector<Material> materials;
  std::vector<Texture> textures;

  std::vector<PointLight> point_lights;
  std::vector<AreaLight> area_lights;
  Environment environment;
  vec3 ambient{0.0f};  // unshadowed ambient radiance times albedo (docs/shading.md)
  // Proxy box of box-projected env-map probes (reflect/box_probe.h); empty = the scene's bounds.
  Bounds3 probe_box;

  std::vector<NamedCamera> cameras;
  std::vector<CameraPath> camera_paths;

  uint32_t dropped_degenerate = 0;  // triangles removed on load (zero area)
};

// Appends `mesh` as a new object with one material; returns the object id.
uint32_t add_object(Scene& scene, const Mesh& mesh, const std::string& name, uint32_t material,
                    const RigidAnimation& animation = {});

// Appends a material; returns its id.
uint32_t add_material(Scene& scene, const Material& material);

Bounds3 scene_bounds(const Scene& scene);
Bounds3 object_bounds(const Scene& scene, uint32_t object);

// Unit geometric normal of a triangle (right-hand rule over its vertex order).
vec3 triangle_normal(const Scene& scene, uint32_t triangle);

// Attributes at barycentrics (u, v) of a triangle: p = (1−u−v)·p0 + u·p1 + v·p2
// (Embree's convention); `barycentric` is that sum for corner values already loaded. The
// shading normal is the interpolated vertex normal made unit, or the triangle's geometric
// normal where the vertex normals cancel.
template <typename T>
T barycentric(const T& a, const T& b, const T& c, float u, float v) {
  return (1.0f - u - v) * a + u * b + v * c;
}
vec3 triangle_point(const Scene& scene, uint32_t triangle, float u, float v);
vec3 shading_normal(const Scene& scene, uint32_t triangle, float u, float v);  // unit
vec2 triangle_uv(const Scene& scene, uint32_t triangle, float u, float v);

// Diffuse color of the material at a surface point (texture applied).
vec3 surface_diffuse(const Scene& scene, uint32_t triangle, float u, float v);

bool has_animation(const Scene& scene);

// The scene at time t: positions and normals of animated objects moved rigidly.
Scene pose_scene(const Scene& rest, float t);

// Checks and repairs a scene after loading: throws InputError (naming `source`) for
// non-finite vertices, out-of-range indices or material ids; drops zero-area triangles,
// counting them in dropped_degenerate; fills missing normals/uvs and replaces non-finite
// ones (normal +Y, uv 0). Keeps object ranges valid.
void sanitize_scene(Scene& scene, const std::string& source);

}  // namespace proxima
