// A balcony: a dark iron railing (61 balusters 3 cm square, a top and a bottom rail) in front
// of a bright plastered facade, on a terrace by a street. Built for GIBR's thin-occluder
// regime (docs/gibr.md): each baluster is a high-contrast silhouette 1–2 photograph pixels
// wide in front of a textured wall, and the light stands high in front so the railing's
// shadows fall on the terrace, not on the facade.
#include <string>

#include "proxima/scene/camera_path.h"
#include "proxima/scene/visibility_models.h"

namespace proxima {
namespace {

enum BoxFace : unsigned {
  kNegX = 1,
  kPosX = 2,
  kNegY = 4,
  kPosY = 8,
  kNegZ = 16,
  kPosZ = 32,
  kAllFaces = 63
};

// The faces of the axis-aligned box [lo, hi] selected by `faces` (BoxFace bits), each one
// outward-facing quad of two triangles, as one object.
void add_box_faces(Scene& s, vec3 lo, vec3 hi, unsigned faces, uint32_t mat, const std::string& name) {
  Mesh m;
  auto face = [&](vec3 corner, vec3 u, vec3 v) {
    const uint32_t b = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), {corner, corner + u, corner + u + v, corner + v});
    m.normals.insert(m.normals.end(), 4, glm::normalize(glm::cross(u, v)));
    m.uvs.insert(m.uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    m.triangles.push_back({b, b + 1, b + 2});
    m.triangles.push_back({b, b + 2, b + 3});
  };
  const vec3 d = hi - lo;
  const vec3 dx(d.x, 0, 0), dy(0, d.y, 0), dz(0, 0, d.z);
  if (faces & kNegX) face(lo, dz, dy);
  if (faces & kPosX) face(lo + dx, dy, dz);
  if (faces & kNegY) face(lo, dx, dz);
  if (faces & kPosY) face(lo + dy, dz, dx);
  if (faces & kNegZ) face(lo, dy, dx);
  if (faces & kPosZ) face(lo + dz, dx, dy);
  add_object(s, m, name, mat);
}

}  // namespace

Scene make_vis_balcony() {
  Scene s;
  s.name = "balcony";
  const uint32_t plaster = add_material(s, {"facade", {0.9f, 0.85f, 0.72f}});
  const uint32_t slab = add_material(s, {"slab", {0.55f, 0.55f, 0.52f}});
  const uint32_t iron = add_material(s, {"railing", {0.06f, 0.06f, 0.07f}});
  // Facade x 0..8 at z = 0, 3.2 m high; a terrace slab 0.15 m high out to z = 1.4; the railing
  // at z = 1.27..1.33: rails 0.04 m high at y 0.08 and 0.98, balusters every 0.125 m between.
  const float L = 8.0f, H = 3.2f, D = 1.4f, z0 = 1.27f, z1 = 1.33f;
  add_box_faces(s, {0, 0, -0.1f}, {L, H, 0}, kPosZ, plaster, "facade");
  add_box_faces(s, {0, -0.15f, 0}, {L, 0, D}, kPosY | kPosZ | kNegX | kPosX, slab, "slab");
  // The street in front, wide and deep enough that every photograph's pose (stepped back,
  // off the path) lies within the model's bounds.
  add_box_faces(s, {-3.0f, -0.25f, D}, {L + 3.0f, -0.15f, 10.0f}, kPosY, slab, "street");
  add_box_faces(s, {0.1f, 0.08f, z0}, {L - 0.1f, 0.12f, z1}, kAllFaces, iron, "bottom_rail");
  add_box_faces(s, {0.1f, 0.98f, z0}, {L - 0.1f, 1.02f, z1}, kAllFaces, iron, "top_rail");
  for (int i = 0; i < 61; ++i) {
    const float x = 0.25f + 0.125f * float(i);
    add_box_faces(s, {x - 0.015f, 0.12f, 1.285f}, {x + 0.015f, 0.98f, 1.315f}, kNegX | kPosX | kNegZ | kPosZ,
                  iron, "baluster_" + std::to_string(i));
  }
  PointLight sun;
  sun.position = {4.0f, 20.0f, 8.0f};
  sun.intensity = vec3(400.0f);
  s.point_lights.push_back(sun);
  s.ambient = vec3(0.25f);
  // In front of the balcony, 1.9 m from the railing, eye 0.3 m above the top rail, looking
  // down at the facade through the balusters and ahead.
  CameraPath p;
  p.name = "walk";
  p.frames = 120;
  for (int i = 0; i <= 6; ++i) {
    const vec3 at(0.8f + 1.05f * float(i), 1.3f, 3.2f);
    p.keys.push_back({float(i), at, at + vec3(0.6f, -0.35f, -3.0f), 65.0f});
  }
  s.camera_paths.push_back(p);
  s.cameras.push_back({"walk_start", camera_at_time(p, frame_time(p, 0), 512, 512, 0.01f, 1000.0f)});
  return s;
}

}  // namespace proxima
