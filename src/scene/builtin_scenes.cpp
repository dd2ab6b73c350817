// Built-in scenes. Each is built from procedural meshes only, so it is deterministic and
// needs no files. The room-reflector scene follows the test room of the distance-corrected
// environment map paper (8 × 8 × 4 m room, a 2,176-triangle mirror cylinder in the middle);
// living-room and bathroom follow the two interiors of the cluster depth image thesis
// (ch. 4: 280k triangles with 130k on reflectors, and 90k with 46k).
#include "proxima/scene/builtin_scenes.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/error.h"
#include "proxima/scene/level_scenes.h"
#include "proxima/scene/procedural.h"
#include "proxima/scene/sampling_scenes.h"
#include "proxima/scene/visibility_models.h"

namespace proxima {
namespace {

// Rectangle corner + a·edge_u + b·edge_v (a, b in [0, 1]) split into n × m quads, facing
// cross(edge_u, edge_v); uv = (a, b)·uv_scale. Grid points are corner + (i/n)·edge_u + … so
// axis-aligned rectangles with dyadic sizes get exact coordinates.
Mesh make_quad(vec3 corner, vec3 edge_u, vec3 edge_v, int n, int m, float uv_scale = 1.0f) {
  Mesh mesh;
  vec3 normal = glm::normalize(glm::cross(edge_u, edge_v));
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) {
      float a = float(i) / float(n), b = float(j) / float(m);
      mesh.positions.push_back(corner + a * edge_u + b * edge_v);
      mesh.normals.push_back(normal);
      mesh.uvs.push_back(uv_scale * vec2(a, b));
    }
  }
  const uint32_t row = uint32_t(n + 1);
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      uint32_t p = uint32_t(j) * row + uint32_t(i);
      mesh.triangles.push_back({p, p + 1, p + 1 + row});
      mesh.triangles.push_back({p, p + 1 + row, p + row});
    }
  }
  return mesh;
}

// Translation · rotation about +Y (degrees) · scale.
mat4 place(vec3 at, float yaw_deg = 0.0f, vec3 scale = vec3(1.0f)) {
  mat4 t = glm::translate(mat4(1.0f), at);
  if (yaw_deg != 0.0f) t = glm::rotate(t, glm::radians(yaw_deg), vec3(0.0f, 1.0f, 0.0f));
  return glm::scale(t, scale);
}

Material material(const std::string& name, vec3 diffuse, float specular = 0.0f,
                  float gloss = 0.0f, vec3 emission = vec3(0.0f)) {
  Material m;
  m.name = name;
  m.diffuse = diffuse;
  m.specular = specular;
  m.gloss = gloss;
  m.emission = emission;
  return m;
}

// Adds `mesh` moved by `transform` as one object.
uint32_t put(Scene& scene, Mesh mesh, const std::string& name, uint32_t mat,
             const mat4& transform = mat4(1.0f)) {
  if (transform != mat4(1.0f)) transform_mesh(mesh, transform);
  return add_object(scene, mesh, name, mat);
}

// Box with its bottom face centered at `base`, rotated `yaw_deg` about +Y.
uint32_t put_box(Scene& scene, const std::string& name, uint32_t mat, vec3 size, vec3 base,
                 float yaw_deg = 0.0f, int subdivisions = 1) {
  return put(scene, make_box(size, subdivisions), name, mat,
             place(base + vec3(0.0f, 0.5f * size.y, 0.0f), yaw_deg));
}

// Six inward-facing walls of the box [lo, hi], each split into quads about `cell` meters
// wide, named "floor", "ceiling", "wall_back", "wall_front", "wall_left", "wall_right"
// (back = −Z, left = −X), with mats[] in that order. Floor uvs run 0..floor_uv_scale.
void put_room(Scene& scene, vec3 lo, vec3 hi, float cell, const uint32_t mats[6],
              float floor_uv_scale = 1.0f) {
  vec3 d = hi - lo;
  auto cells = [&](float len) { return std::max(1, int(std::lround(len / cell))); };
  put(scene, make_quad({lo.x, lo.y, hi.z}, {d.x, 0, 0}, {0, 0, -d.z}, cells(d.x), cells(d.z),
                       floor_uv_scale),
      "floor", mats[0]);
  put(scene, make_quad({lo.x, hi.y, lo.z}, {d.x, 0, 0}, {0, 0, d.z}, cells(d.x), cells(d.z)),
      "ceiling", mats[1]);
  put(scene, make_quad({lo.x, lo.y, lo.z}, {d.x, 0, 0}, {0, d.y, 0}, cells(d.x), cells(d.y)),
      "wall_back", mats[2]);
  put(scene, make_quad({hi.x, lo.y, hi.z}, {-d.x, 0, 0}, {0, d.y, 0}, cells(d.x), cells(d.y)),
      "wall_front", mats[3]);
  put(scene, make_quad({lo.x, lo.y, hi.z}, {0, 0, -d.z}, {0, d.y, 0}, cells(d.z), cells(d.y)),
      "wall_left", mats[4]);
  put(scene, make_quad({hi.x, lo.y, lo.z}, {0, 0, d.z}, {0, d.y, 0}, cells(d.z), cells(d.y)),
      "wall_right", mats[5]);
}

// Two-color checkerboard, `checks` × `checks` squares over the texture (for recognizable
// reflections of the floor).
uint32_t add_checker(Scene& scene, const std::string& name, vec3 a, vec3 b, int checks) {
  const int size = 64;
  Texture tex;
  tex.name = name;
  tex.image = ImageF(size, size, 3);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      vec3 c = ((x * checks / size + y * checks / size) % 2 == 0) ? a : b;
      for (int k = 0; k < 3; ++k) tex.image.at(x, y, k) = c[k];
    }
  }
  scene.textures.push_back(std::move(tex));
  return uint32_t(scene.textures.size() - 1);
}

// A camera loop around `center` at `radius` and `height` (relative to center), looking at
// center + (0, target_height, 0); one key per second, the last key back at the start.
CameraPath orbit_path(const std::string& name, vec3 center, float radius, float height,
                      float target_height, float seconds, float vfov_deg) {
  CameraPath path;
  path.name = name;
  path.frames = 100;
  const int keys = int(seconds);
  for (int k = 0; k <= keys; ++k) {
    float phi = 2.0f * kPi * float(k) / float(keys);
    path.keys.push_back({float(k), center + vec3(radius * std::sin(phi), height, radius * std::cos(phi)),
                         center + vec3(0.0f, target_height, 0.0f), vfov_deg});
  }
  return path;
}

NamedCamera camera(const std::string& name, vec3 eye, vec3 target, float vfov_deg) {
  return {name, look_at(eye, target, vec3(0.0f, 1.0f, 0.0f), vfov_deg, 512, 512)};
}

// A square ceiling lamp of side `side` over x, z ∈ [corner, corner + side]: the emitting
// quad (object `name`) at height `quad_y` and the area light that samples it just below,
// at corner.y.
void put_ceiling_lamp(Scene& s, const std::string& name, uint32_t emitter, vec3 corner, float quad_y, float side,
                      vec3 radiance) {
  put(s, make_quad({corner.x, quad_y, corner.z}, {side, 0, 0}, {0, 0, side}, 1, 1), name, emitter);
  AreaLight light;
  light.corner = corner;
  light.edge_u = {side, 0.0f, 0.0f};
  light.edge_v = {0.0f, 0.0f, side};
  light.radiance = radiance;
  s.area_lights.push_back(light);
}

// ---- cornell ---------------------------------------------------------------------------
// The layout is exact and relied on by analytic tests; see builtin_scenes.h.
Scene make_cornell() {
  Scene s;
  s.name = "cornell";
  const uint32_t white = add_material(s, material("white", vec3(0.75f)));
  const uint32_t red = add_material(s, material("red", {0.75f, 0.1f, 0.1f}));
  const uint32_t green = add_material(s, material("green", {0.1f, 0.75f, 0.1f}));
  const uint32_t mirror = add_material(s, material("mirror", vec3(0.9f), 1.0f, 0.0f));
  const uint32_t glossy = add_material(s, material("glossy", vec3(0.7f), 0.5f, 0.3f));
  const uint32_t emitter = add_material(s, material("light", vec3(0.0f), 0, 0, vec3(12.0f)));

  put(s, make_quad({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 8, 8), "floor", white);
  put(s, make_quad({-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, 8, 8), "ceiling", white);
  put(s, make_quad({-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, 8, 8), "back_wall", white);
  put(s, make_quad({-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, 8, 8), "left_wall", red);
  put(s, make_quad({1, 0, -1}, {0, 0, 2}, {0, 2, 0}, 8, 8), "right_wall", green);
  put(s, make_sphere(0.4f, 64, 32), "mirror_sphere", mirror, place({-0.4f, 0.4f, -0.2f}));
  put(s, make_box({0.5f, 1.0f, 0.5f}), "glossy_block", glossy, place({0.45f, 0.5f, -0.35f}, 20.0f));
  put_ceiling_lamp(s, "light", emitter, {-0.25f, 1.98f, -0.25f}, 1.985f, 0.5f, vec3(12.0f));
  s.ambient = vec3(0.03f);
  s.environment.color = vec3(0.0f);
  s.cameras.push_back(camera("front", {0, 1, 3.5f}, {0, 1, 0}, 40.0f));
  return s;
}

// ---- the env-map test room (room-reflector, room-parallax) -----------------------------
// The floor of 1 m checks; its checker texture is added to `s`.
Material checker_floor(Scene& s) {
  Material floor = material("floor_checker", vec3(1.0f));
  floor.diffuse_texture = int(add_checker(s, "checker", vec3(0.8f), {0.15f, 0.15f, 0.2f}, 2));
  return floor;
}

// The 8 × 8 × 4 m room (x, z ∈ [−4, 4]): `floor`, a ceiling and four colored walls, the
// second of them `front`.
void put_test_room(Scene& s, const Material& floor, const Material& front) {
  const uint32_t walls[6] = {
      add_material(s, floor),
      add_material(s, material("ceiling", vec3(0.85f))),
      add_material(s, material("wall_blue", {0.35f, 0.45f, 0.75f})),
      add_material(s, front),
      add_material(s, material("wall_red", {0.7f, 0.25f, 0.2f})),
      add_material(s, material("wall_green", {0.3f, 0.65f, 0.3f})),
  };
  // Floor uvs 0..4 with 2 × 2 checks per texture tile: 1 m squares.
  put_room(s, {-4, 0, -4}, {4, 4, 4}, 0.25f, walls, 4.0f);
}

// The room's centre piece: the mirror cylinder (64 segments × 16 bands + caps = 2,176
// triangles, as in the paper) and the 1 m² ceiling lamp above it, an area light.
void put_reflector_and_lamp(Scene& s) {
  const uint32_t mirror = add_material(s, material("mirror", vec3(0.9f), 1.0f, 0.0f));
  const uint32_t lamp = add_material(s, material("lamp", vec3(0.0f), 0, 0, vec3(5.0f)));
  put(s, make_cylinder(0.5f, 2.0f, 64, 16, true), "reflector", mirror);
  put_ceiling_lamp(s, "light", lamp, {-0.5f, 3.98f, -0.5f}, 3.99f, 1.0f, vec3(5.0f));
}

// ---- room-reflector --------------------------------------------------------------------
Scene make_room_reflector() {
  Scene s;
  s.name = "room-reflector";
  put_test_room(s, checker_floor(s), material("wall_beige", {0.8f, 0.7f, 0.5f}));

  const uint32_t wood = add_material(s, material("wood", {0.55f, 0.35f, 0.2f}));
  const uint32_t dark = add_material(s, material("dark_wood", {0.3f, 0.18f, 0.1f}));
  const uint32_t yellow = add_material(s, material("yellow", {0.9f, 0.8f, 0.15f}));
  const uint32_t red = add_material(s, material("red", {0.85f, 0.1f, 0.1f}));
  const uint32_t blue = add_material(s, material("blue", {0.1f, 0.2f, 0.85f}));
  const uint32_t orange = add_material(s, material("orange", {0.95f, 0.5f, 0.1f}));
  const uint32_t white = add_material(s, material("white", vec3(0.9f)));

  // Furniture against the walls, so the cylinder reflects something in every direction.
  put_box(s, "table_top", wood, {1.6f, 0.06f, 0.9f}, {-2.2f, 0.74f, -2.4f}, 0, 4);
  for (int k = 0; k < 4; ++k) {
    float x = -2.2f + (k % 2 == 0 ? -0.7f : 0.7f), z = -2.4f + (k / 2 == 0 ? -0.35f : 0.35f);
    put_box(s, "table_leg_" + std::to_string(k), dark, {0.06f, 0.74f, 0.06f}, {x, 0, z});
  }
  put_box(s, "cabinet", dark, {0.6f, 1.8f, 2.0f}, {3.65f, 0, -1.0f}, 0, 4);
  put_box(s, "sofa_seat", blue, {2.2f, 0.45f, 0.9f}, {0.5f, 0, 3.5f}, 0, 4);
  put_box(s, "sofa_back", blue, {2.2f, 0.5f, 0.2f}, {0.5f, 0.45f, 3.85f}, 0, 4);
  put_box(s, "crate", orange, {0.7f, 0.7f, 0.7f}, {-3.0f, 0, 2.6f}, 30.0f, 4);
  put(s, make_sphere(0.35f, 48, 24), "red_ball", red, place({2.0f, 0.35f, 1.6f}));
  put(s, make_torus(0.3f, 0.1f, 48, 24), "blue_ring", blue, place({-1.8f, 0.1f, 0.6f}));
  put(s, make_teapot(6), "teapot", yellow, place({-2.2f, 0.8f, -2.4f}, 30.0f, vec3(0.35f)));
  put(s, make_cylinder(0.2f, 1.2f, 32, 4, true), "column", white, place({2.4f, 0, -2.6f}));
  put_reflector_and_lamp(s);

  s.point_lights.push_back({{2.5f, 3.5f, 2.5f}, vec3(8.0f)});
  s.ambient = vec3(0.05f);
  s.cameras.push_back(camera("main", {0, 1.7f, 3.2f}, {0, 1.0f, 0}, 60.0f));
  s.cameras.push_back(camera("corner", {-3.2f, 2.8f, -3.2f}, {0, 0.9f, 0}, 60.0f));
  s.camera_paths.push_back(orbit_path("orbit", vec3(0.0f), 2.8f, 1.6f, 1.0f, 8.0f, 60.0f));
  return s;
}

// Horizontal bar: cylinder of `length` along +X starting at `start`.
mat4 along_x(vec3 start, float length_scale = 1.0f) {
  mat4 t = glm::translate(mat4(1.0f), start);
  t = glm::rotate(t, glm::radians(-90.0f), vec3(0.0f, 0.0f, 1.0f));  // +Y → +X
  return glm::scale(t, vec3(1.0f, length_scale, 1.0f));
}

// ---- living-room -----------------------------------------------------------------------
// 8 × 6 × 3 m room (x ∈ [−4, 4], z ∈ [−3, 3]): sofa on the back wall, coffee table, TV on the
// front wall, shelves on the left wall, a mirror on the right one, reflective teapots, vases,
// a chrome lamp and sculpture, a mirror-polished floor inlay.
Scene make_living_room() {
  Scene s;
  s.name = "living-room";
  const uint32_t room[6] = {
      add_material(s, material("oak_floor", {0.55f, 0.38f, 0.22f})),
      add_material(s, material("ceiling", vec3(0.9f))),
      add_material(s, material("wall_cream", {0.85f, 0.8f, 0.68f})),
      add_material(s, material("wall_cream_front", {0.85f, 0.8f, 0.68f})),
      add_material(s, material("wall_sage", {0.55f, 0.65f, 0.5f})),
      add_material(s, material("wall_terracotta", {0.75f, 0.45f, 0.35f})),
  };
  put_room(s, {-4, 0, -3}, {4, 3, 3}, 0.0625f, room);

  const uint32_t fabric = add_material(s, material("sofa_fabric", {0.25f, 0.3f, 0.45f}));
  const uint32_t cushion = add_material(s, material("cushion", {0.8f, 0.55f, 0.2f}));
  const uint32_t leather = add_material(s, material("leather", {0.45f, 0.25f, 0.12f}));
  const uint32_t wood = add_material(s, material("walnut", {0.35f, 0.2f, 0.1f}));
  const uint32_t rug = add_material(s, material("rug", {0.6f, 0.15f, 0.15f}));
  const uint32_t leaf = add_material(s, material("leaf", {0.15f, 0.5f, 0.15f}));
  const uint32_t clay = add_material(s, material("clay_pot", {0.7f, 0.4f, 0.25f}));
  const uint32_t shade = add_material(s, material("lamp_shade", {0.95f, 0.9f, 0.75f}));
  const uint32_t curtain = add_material(s, material("curtain", {0.7f, 0.65f, 0.8f}));
  const uint32_t black = add_material(s, material("tv_body", vec3(0.05f)));
  const uint32_t panel = add_material(s, material("ceiling_light", vec3(0.0f), 0, 0, vec3(6.0f)));
  const uint32_t book_mats[4] = {
      add_material(s, material("book_red", {0.7f, 0.1f, 0.1f})),
      add_material(s, material("book_blue", {0.1f, 0.2f, 0.6f})),
      add_material(s, material("book_green", {0.15f, 0.5f, 0.2f})),
      add_material(s, material("book_yellow", {0.85f, 0.75f, 0.2f})),
  };
  const uint32_t mirror = add_material(s, material("mirror", vec3(0.9f), 1.0f, 0.0f));
  const uint32_t chrome = add_material(s, material("chrome", vec3(0.8f), 0.9f, 0.0f));
  const uint32_t brushed = add_material(s, material("brushed_steel", vec3(0.7f), 0.7f, 0.25f));
  const uint32_t copper = add_material(s, material("copper", {0.9f, 0.5f, 0.3f}, 0.7f, 0.15f));
  const uint32_t ceramic = add_material(s, material("glazed_ceramic", {0.9f, 0.9f, 0.85f}, 0.3f, 0.4f));
  const uint32_t vase_glaze[4] = {
      add_material(s, material("glaze_blue", {0.1f, 0.25f, 0.7f}, 0.4f, 0.1f)),
      add_material(s, material("glaze_green", {0.2f, 0.6f, 0.3f}, 0.3f, 0.5f)),
      add_material(s, material("silvered_glass", vec3(0.85f), 1.0f, 0.0f)),
      add_material(s, material("glaze_red", {0.7f, 0.1f, 0.1f}, 0.35f, 0.2f)),
  };
  const uint32_t lacquer = add_material(s, material("lacquered_wood", {0.3f, 0.15f, 0.08f}, 0.4f, 0.15f));
  const uint32_t screen = add_material(s, material("tv_screen", vec3(0.02f), 0.5f, 0.05f));
  const uint32_t glass = add_material(s, material("glass_top", vec3(0.1f), 0.8f, 0.0f));

  // Sofa on the back wall, facing +Z.
  put_box(s, "sofa_base", fabric, {2.6f, 0.42f, 0.95f}, {0, 0, -2.5f}, 0, 10);
  put_box(s, "sofa_back", fabric, {2.6f, 0.5f, 0.25f}, {0, 0.42f, -2.85f}, 0, 10);
  put_box(s, "sofa_arm_left", fabric, {0.25f, 0.3f, 0.95f}, {-1.42f, 0.42f, -2.5f}, 0, 8);
  put_box(s, "sofa_arm_right", fabric, {0.25f, 0.3f, 0.95f}, {1.42f, 0.42f, -2.5f}, 0, 8);
  for (int k = 0; k < 3; ++k) {
    put_box(s, "sofa_cushion_" + std::to_string(k), cushion, {0.82f, 0.14f, 0.68f},
            {-0.86f + 0.86f * float(k), 0.42f, -2.38f}, 0, 10);
    put(s, make_torus(0.14f, 0.06f, 48, 24), "round_cushion_" + std::to_string(k), cushion,
        place({-0.86f + 0.86f * float(k), 0.76f, -2.62f}, 0.0f, {1.0f, 1.0f, 0.6f}) *
            glm::rotate(mat4(1.0f), glm::radians(80.0f), vec3(1, 0, 0)));
  }
  // Armchairs either side of the coffee table, turned toward it.
  for (int side = 0; side < 2; ++side) {
    float sx = side == 0 ? -1.0f : 1.0f;
    std::string tag = side == 0 ? "_left" : "_right";
    vec3 c{2.3f * sx, 0.0f, -0.9f};
    float yaw = -90.0f * sx;  // seat faces the room center
    mat4 frame = place(c, yaw);
    auto part = [&](const std::string& name, vec3 size, vec3 base) {
      put(s, make_box(size, 8), name + tag, leather,
          frame * place(base + vec3(0.0f, 0.5f * size.y, 0.0f)));
    };
    part("armchair_seat", {0.85f, 0.42f, 0.8f}, {0, 0, 0});
    part("armchair_back", {0.85f, 0.55f, 0.18f}, {0, 0.42f, -0.31f});
    part("armchair_arm_a", {0.14f, 0.25f, 0.8f}, {-0.36f, 0.42f, 0});
    part("armchair_arm_b", {0.14f, 0.25f, 0.8f}, {0.36f, 0.42f, 0});
  }
  // Coffee table: lacquered top on chrome legs, teapot and bowl on it.
  put_box(s, "coffee_table_top", lacquer, {1.3f, 0.05f, 0.75f}, {0, 0.42f, -0.9f}, 0, 24);
  for (int k = 0; k < 4; ++k) {
    float x = k % 2 == 0 ? -0.58f : 0.58f, z = -0.9f + (k / 2 == 0 ? -0.3f : 0.3f);
    put(s, make_cylinder(0.025f, 0.42f, 32, 4, true), "coffee_table_leg_" + std::to_string(k),
        chrome, place({x, 0, z}));
  }
  put(s, make_teapot(16), "teapot_chrome", chrome, place({-0.25f, 0.47f, -0.9f}, 20.0f, vec3(0.25f)));
  put(s, make_sphere(0.16f, 64, 32), "bowl_copper", copper, place({0.35f, 0.542f, -0.85f}, 0, {1, 0.45f, 1}));
  put(s, make_quad({-1.4f, 0.001f, 0.1f}, {2.8f, 0, 0}, {0, 0, -2.0f}, 64, 48), "rug", rug);
  // Mirror-polished floor inlay between the table and the TV.
  put(s, make_plane(2.0f, 1.6f, 40, 32), "floor_mirror", mirror, place({0, 0.002f, 1.3f}));

  // TV wall (+Z): low cabinet, TV, vases, curtains framing a window-less wall.
  put_box(s, "tv_cabinet", wood, {2.4f, 0.5f, 0.45f}, {0, 0, 2.75f}, 0, 12);
  put_box(s, "tv_body", black, {1.6f, 0.92f, 0.06f}, {0, 0.95f, 2.94f}, 0, 4);
  put(s, make_quad({0.76f, 0.99f, 2.905f}, {-1.52f, 0, 0}, {0, 0.84f, 0}, 48, 27), "tv_screen", screen);
  for (int k = 0; k < 2; ++k) {
    float x = k == 0 ? -0.95f : 0.95f;
    put(s, make_sphere(1.0f, 112, 56), "vase_" + std::to_string(k), vase_glaze[k],
        place({x, 0.5f + 0.24f, 2.75f}, 0, {0.11f, 0.24f, 0.11f}));
  }
  for (int k = 0; k < 2; ++k) {
    float x = k == 0 ? -2.3f : 2.3f;
    put(s, make_quad({x + 0.5f, 0.05f, 2.95f}, {-1.0f, 0, 0}, {0, 2.8f, 0}, 32, 64),
        "curtain_" + std::to_string(k), curtain);
  }

  // Shelves on the left wall (−X) with books, a teapot, a vase and chrome balls.
  put_box(s, "shelf_side_a", wood, {0.35f, 2.2f, 0.04f}, {-3.8f, 0, -1.0f}, 0, 4);
  put_box(s, "shelf_side_b", wood, {0.35f, 2.2f, 0.04f}, {-3.8f, 0, 1.0f}, 0, 4);
  for (int level = 0; level < 5; ++level) {
    float y = 0.1f + 0.5f * float(level);
    put_box(s, "shelf_board_" + std::to_string(level), wood, {0.35f, 0.03f, 2.0f}, {-3.8f, y, 0}, 0, 4);
  }
  // Books: fixed pseudo-random widths and heights, so the layout is deterministic.
  for (int level = 0; level < 4; ++level) {
    float y = 0.13f + 0.5f * float(level);
    float z = -0.95f;
    for (int b = 0; z < (level % 2 == 0 ? 0.2f : -0.1f); ++b) {
      uint32_t h = uint32_t(level * 31 + b * 17);
      float width = 0.03f + 0.01f * float(h % 4);
      float height = 0.22f + 0.03f * float((h / 4) % 5);
      put_box(s, "book_" + std::to_string(level) + "_" + std::to_string(b), book_mats[h % 4],
              {0.22f, height, width}, {-3.82f, y, z + 0.5f * width});
      z += width + 0.004f;
    }
  }
  put(s, make_teapot(16), "teapot_ceramic", ceramic, place({-3.78f, 1.63f, 0.5f}, 90.0f, vec3(0.2f)));
  put(s, make_teapot(16), "teapot_copper", copper, place({-3.78f, 0.63f, 0.6f}, -60.0f, vec3(0.18f)));
  put(s, make_sphere(1.0f, 112, 56), "vase_2", vase_glaze[2], place({-3.8f, 2.33f, 0.45f}, 0, {0.09f, 0.2f, 0.09f}));
  for (int k = 0; k < 3; ++k) {
    put(s, make_sphere(0.06f, 48, 24), "chrome_ball_" + std::to_string(k), chrome,
        place({-3.78f, 1.19f, 0.3f + 0.15f * float(k)}));
  }

  // Right wall (+X): mirror, side table with a vase, floor lamp in the back corner.
  put(s, make_quad({3.995f, 0.8f, -0.6f}, {0, 0, 1.2f}, {0, 1.6f, 0}, 16, 16), "wall_mirror", mirror);
  put(s, make_cylinder(0.3f, 0.04f, 64, 2, true), "side_table_top", glass, place({3.3f, 0.6f, 1.4f}));
  put(s, make_cylinder(0.03f, 0.6f, 32, 4, true), "side_table_stem", brushed, place({3.3f, 0, 1.4f}));
  put(s, make_sphere(1.0f, 112, 56), "vase_3", vase_glaze[3], place({3.3f, 0.64f + 0.2f, 1.4f}, 0, {0.1f, 0.2f, 0.1f}));
  put(s, make_cylinder(0.18f, 0.03f, 64, 2, true), "lamp_base", chrome, place({3.3f, 0, -2.4f}));
  put(s, make_cylinder(0.015f, 1.6f, 32, 32, true), "lamp_pole", chrome, place({3.3f, 0.03f, -2.4f}));
  put(s, make_cylinder(0.22f, 0.3f, 64, 8, false), "lamp_shade", shade, place({3.3f, 1.55f, -2.4f}));
  put(s, make_torus(0.22f, 0.05f, 96, 48), "sculpture", chrome,
      place({0.45f, 0.5f + 0.27f, 2.75f}, 30.0f) * glm::rotate(mat4(1.0f), glm::radians(90.0f), vec3(1, 0, 0)));

  // Plants in the front corners: clay pots with spherical foliage.
  for (int k = 0; k < 2; ++k) {
    float x = k == 0 ? -3.5f : 3.5f;
    std::string tag = std::to_string(k);
    put(s, make_cylinder(0.22f, 0.4f, 64, 8, true), "plant_pot_" + tag, clay, place({x, 0, 2.5f}));
    for (int b = 0; b < 3; ++b) {
      float a = 2.0f * kPi * float(b) / 3.0f;
      put(s, make_sphere(0.22f, 64, 32), "plant_foliage_" + tag + "_" + std::to_string(b), leaf,
          place({x + 0.12f * std::cos(a), 0.75f + 0.15f * float(b), 2.5f + 0.12f * std::sin(a)}));
    }
  }
  // Ceiling light panel (emissive geometry for the area light below it).
  put_ceiling_lamp(s, "ceiling_light", panel, {-0.6f, 2.99f, -1.2f}, 2.995f, 1.2f, vec3(6.0f));
  s.point_lights.push_back({{3.3f, 1.65f, -2.4f}, vec3(3.0f)});  // inside the lamp shade
  s.point_lights.push_back({{-2.0f, 2.6f, 1.5f}, vec3(4.0f)});
  s.ambient = vec3(0.04f);

  s.cameras.push_back(camera("overview", {3.6f, 2.4f, 2.6f}, {-0.5f, 0.6f, -0.8f}, 60.0f));
  s.cameras.push_back(camera("table", {0.9f, 1.0f, 0.4f}, {-0.1f, 0.45f, -0.9f}, 50.0f));

  CameraPath walk;
  walk.name = "walk";
  walk.frames = 100;
  walk.keys = {
      CameraKey{0.0f, {3.2f, 1.6f, 2.4f}, {0.0f, 0.8f, -1.0f}, 60.0f},
      CameraKey{2.5f, {1.5f, 1.5f, 1.6f}, {-1.0f, 0.7f, -1.2f}, 60.0f},
      CameraKey{5.0f, {-0.5f, 1.4f, 1.2f}, {-3.0f, 1.0f, 0.0f}, 60.0f},
      CameraKey{7.5f, {-1.8f, 1.5f, 0.8f}, {0.0f, 0.5f, -0.9f}, 55.0f},
      CameraKey{10.0f, {-2.6f, 1.7f, -1.6f}, {2.0f, 0.8f, 1.0f}, 60.0f},
  };
  s.camera_paths.push_back(walk);
  s.camera_paths.push_back(orbit_path("orbit", {0.0f, 0.0f, -0.9f}, 1.6f, 1.3f, 0.5f, 10.0f, 55.0f));
  return s;
}

// ---- bathroom --------------------------------------------------------------------------
// 4 × 3 × 2.5 m room (x ∈ [−2, 2], z ∈ [−1.5, 1.5]): glossy tiles on the floor and two walls,
// a wall mirror over the sink, an enamel tub, a toilet and chrome fixtures.
Scene make_bathroom() {
  Scene s;
  s.name = "bathroom";
  const uint32_t floor_tile = add_material(s, material("floor_tile", {0.35f, 0.38f, 0.42f}, 0.2f, 0.4f));
  const uint32_t wall_tile = add_material(s, material("wall_tile", {0.75f, 0.85f, 0.9f}, 0.25f, 0.3f));
  const uint32_t paint = add_material(s, material("wall_paint", {0.9f, 0.88f, 0.8f}));
  const uint32_t room[6] = {
      floor_tile, add_material(s, material("ceiling", vec3(0.92f))), wall_tile, paint, wall_tile, paint,
  };
  put_room(s, {-2, 0, -1.5f}, {2, 2.5f, 1.5f}, 0.0625f, room);

  const uint32_t mirror = add_material(s, material("mirror", vec3(0.9f), 1.0f, 0.0f));
  const uint32_t chrome = add_material(s, material("chrome", vec3(0.8f), 0.9f, 0.0f));
  const uint32_t satin = add_material(s, material("satin_nickel", vec3(0.7f), 0.6f, 0.35f));
  const uint32_t enamel = add_material(s, material("enamel", vec3(0.95f), 0.3f, 0.2f));
  const uint32_t porcelain = add_material(s, material("porcelain", vec3(0.92f), 0.35f, 0.1f));
  const uint32_t glass = add_material(s, material("glass_shelf", vec3(0.1f), 0.8f, 0.0f));
  const uint32_t cabinet = add_material(s, material("cabinet", {0.4f, 0.28f, 0.18f}));
  const uint32_t door = add_material(s, material("door", {0.85f, 0.85f, 0.82f}));
  const uint32_t towel_mats[3] = {
      add_material(s, material("towel_teal", {0.1f, 0.5f, 0.5f})),
      add_material(s, material("towel_coral", {0.9f, 0.45f, 0.35f})),
      add_material(s, material("towel_white", vec3(0.85f))),
  };
  const uint32_t mat = add_material(s, material("bath_mat", {0.3f, 0.35f, 0.6f}));
  const uint32_t leaf = add_material(s, material("leaf", {0.15f, 0.5f, 0.15f}));
  const uint32_t pot = add_material(s, material("plant_pot", {0.7f, 0.4f, 0.25f}));
  const uint32_t wicker = add_material(s, material("wicker", {0.6f, 0.45f, 0.25f}));
  const uint32_t bottle_mats[3] = {
      add_material(s, material("bottle_blue", {0.2f, 0.3f, 0.8f})),
      add_material(s, material("bottle_pink", {0.85f, 0.4f, 0.6f})),
      add_material(s, material("bottle_amber", {0.8f, 0.5f, 0.1f})),
  };
  const uint32_t lamp = add_material(s, material("ceiling_light", vec3(0.0f), 0, 0, vec3(8.0f)));

  // Tub along the left wall (−X), faucet and spout at its back end.
  put_box(s, "tub", enamel, {0.75f, 0.55f, 1.7f}, {-1.6f, 0, -0.6f}, 0, 16);
  put(s, make_cylinder(0.025f, 0.25f, 48, 8, true), "tub_faucet", chrome, place({-1.6f, 0.55f, -1.42f}));
  put(s, make_torus(0.08f, 0.018f, 48, 24), "tub_spout", chrome,
      place({-1.6f, 0.8f, -1.34f}, 90.0f) * glm::rotate(mat4(1.0f), glm::radians(90.0f), vec3(1, 0, 0)));
  put(s, make_cylinder(0.012f, 1.2f, 32, 16, true), "shower_pipe", chrome, place({-1.6f, 0.85f, -1.47f}));
  put(s, make_sphere(1.0f, 64, 32), "shower_head", chrome, place({-1.6f, 2.05f, -1.4f}, 0, {0.09f, 0.03f, 0.09f}));
  put(s, make_torus(0.06f, 0.012f, 48, 24), "soap_dish", chrome, place({-1.9f, 0.9f, -0.2f}));

  // Sink unit on the back wall (−Z), the mirror above it and a glass shelf above that.
  put_box(s, "vanity", cabinet, {0.9f, 0.8f, 0.5f}, {0.4f, 0, -1.25f}, 0, 12);
  put(s, make_sphere(1.0f, 64, 32), "sink_basin", porcelain, place({0.4f, 0.86f, -1.22f}, 0, {0.25f, 0.08f, 0.18f}));
  put(s, make_cylinder(0.018f, 0.22f, 48, 8, true), "sink_faucet", chrome, place({0.4f, 0.8f, -1.44f}));
  put(s, make_torus(0.06f, 0.014f, 48, 24), "sink_spout", chrome,
      place({0.4f, 1.02f, -1.38f}, 90.0f) * glm::rotate(mat4(1.0f), glm::radians(90.0f), vec3(1, 0, 0)));
  put(s, make_quad({-0.05f, 1.1f, -1.495f}, {0.9f, 0, 0}, {0, 0.9f, 0}, 32, 32), "mirror", mirror);
  put_box(s, "glass_shelf", glass, {0.6f, 0.015f, 0.14f}, {0.4f, 2.03f, -1.43f}, 0, 2);
  for (int k = 0; k < 3; ++k) {
    put(s, make_cylinder(0.03f, 0.16f - 0.02f * float(k), 48, 12, true), "bottle_" + std::to_string(k),
        bottle_mats[k], place({0.22f + 0.16f * float(k), 2.045f, -1.43f}));
  }

  // Toilet by the right wall (+X): glazed bowl and tank.
  put(s, make_sphere(1.0f, 64, 32), "toilet_bowl", porcelain, place({1.5f, 0.25f, -0.95f}, 0, {0.2f, 0.25f, 0.26f}));
  put_box(s, "toilet_tank", porcelain, {0.42f, 0.85f, 0.18f}, {1.5f, 0.0f, -1.38f}, 0, 8);
  put(s, make_cylinder(0.02f, 0.03f, 32, 2, true), "flush_button", chrome, place({1.5f, 0.85f, -1.38f}));

  // Towel rail on the right wall with towels, a heated ladder rail beside the door.
  put(s, make_cylinder(0.015f, 0.8f, 48, 16, true), "towel_rail", chrome, along_x({-1.4f, 1.3f, 1.45f}));
  for (int k = 0; k < 3; ++k) {
    put_box(s, "towel_" + std::to_string(k), towel_mats[k], {0.22f, 0.6f, 0.04f},
            {-1.25f + 0.26f * float(k), 0.72f, 1.43f}, 0, 6);
  }
  for (int k = 0; k < 6; ++k) {
    put(s, make_cylinder(0.012f, 0.5f, 32, 8, true), "ladder_rung_" + std::to_string(k), satin,
        along_x({1.35f, 0.6f + 0.2f * float(k), 1.46f}));
  }
  put(s, make_cylinder(0.018f, 1.2f, 32, 16, true), "ladder_side_a", satin, place({1.35f, 0.5f, 1.46f}));
  put(s, make_cylinder(0.018f, 1.2f, 32, 16, true), "ladder_side_b", satin, place({1.85f, 0.5f, 1.46f}));

  // Door on the front wall, bath mat, plant, laundry basket.
  put(s, make_quad({0.9f, 0.0f, 1.495f}, {-0.8f, 0, 0}, {0, 2.0f, 0}, 16, 32), "door", door);
  put(s, make_quad({-0.9f, 0.002f, 0.3f}, {0.8f, 0, 0}, {0, 0, -0.5f}, 40, 24), "bath_mat", mat);
  put(s, make_cylinder(0.14f, 0.3f, 64, 8, true), "plant_pot", pot, place({1.75f, 0, 0.2f}));
  for (int b = 0; b < 4; ++b) {
    float a = 2.0f * kPi * float(b) / 4.0f;
    put(s, make_sphere(0.14f, 64, 32), "plant_foliage_" + std::to_string(b), leaf,
        place({1.75f + 0.08f * std::cos(a), 0.45f + 0.1f * float(b), 0.2f + 0.08f * std::sin(a)}));
  }
  put(s, make_cylinder(0.2f, 0.5f, 64, 8, true), "laundry_basket", wicker, place({1.6f, 0, 0.9f}));
  put_ceiling_lamp(s, "ceiling_light", lamp, {-0.4f, 2.49f, -0.4f}, 2.495f, 0.8f, vec3(8.0f));
  s.point_lights.push_back({{0.4f, 2.0f, -1.0f}, vec3(2.0f)});  // above the mirror
  s.ambient = vec3(0.05f);

  s.cameras.push_back(camera("door", {0.5f, 1.6f, 1.3f}, {-0.2f, 0.9f, -1.0f}, 65.0f));
  s.cameras.push_back(camera("mirror", {0.2f, 1.5f, 0.2f}, {0.4f, 1.3f, -1.5f}, 55.0f));
  CameraPath walk;
  walk.name = "walk";
  walk.frames = 100;
  walk.keys = {
      CameraKey{0.0f, {0.5f, 1.6f, 1.3f}, {0.4f, 1.0f, -1.5f}, 65.0f},
      CameraKey{3.0f, {0.2f, 1.6f, 0.4f}, {-1.6f, 0.6f, -0.6f}, 60.0f},
      CameraKey{6.0f, {-0.4f, 1.5f, 0.0f}, {1.5f, 0.5f, -1.0f}, 60.0f},
      CameraKey{10.0f, {0.6f, 1.5f, -0.4f}, {0.4f, 1.4f, -1.5f}, 55.0f},
  };
  s.camera_paths.push_back(walk);
  // Standing by the door and turning from the tub over the mirror to the toilet and rail.
  CameraPath pan;
  pan.name = "pan";
  pan.frames = 100;
  pan.keys = {
      CameraKey{0.0f, {0.2f, 1.6f, 1.1f}, {-1.6f, 0.6f, -0.6f}, 60.0f},
      CameraKey{4.0f, {0.3f, 1.6f, 1.0f}, {0.4f, 1.4f, -1.5f}, 60.0f},
      CameraKey{7.0f, {0.4f, 1.6f, 0.9f}, {1.5f, 0.4f, -0.9f}, 60.0f},
      CameraKey{10.0f, {0.3f, 1.6f, 0.6f}, {1.6f, 1.0f, 1.4f}, 60.0f},
  };
  s.camera_paths.push_back(pan);
  return s;
}

// ---- room-teapot, room-parallax (environment maps with distance) ---------------------
// `src` without the object named `name` (every other object, material, light, camera kept).
Scene without_object(const Scene& src, const std::string& name) {
  Scene s;
  s.materials = src.materials;
  s.textures = src.textures;
  s.point_lights = src.point_lights;
  s.area_lights = src.area_lights;
  s.environment = src.environment;
  s.ambient = src.ambient;
  s.cameras = src.cameras;
  s.camera_paths = src.camera_paths;
  for (const Object& o : src.objects) {
    if (o.name == name) continue;
    Mesh m;
    m.positions.assign(src.positions.begin() + o.first_vertex, src.positions.begin() + o.first_vertex + o.vertex_count);
    m.normals.assign(src.normals.begin() + o.first_vertex, src.normals.begin() + o.first_vertex + o.vertex_count);
    m.uvs.assign(src.uvs.begin() + o.first_vertex, src.uvs.begin() + o.first_vertex + o.vertex_count);
    for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t)
      m.triangles.push_back(src.triangles[t] - uvec3(o.first_vertex));
    add_object(s, m, o.name, src.triangle_material[o.first_triangle], o.animation);
  }
  return s;
}

// room-reflector with its cylinder replaced by a 39,800-triangle mirror teapot (the
// paper's second reflector is a 39,748-face car).
Scene make_room_teapot() {
  Scene s = without_object(make_room_reflector(), "reflector");
  s.name = "room-teapot";
  const uint32_t mirror = add_material(s, material("teapot_mirror", vec3(0.9f), 1.0f, 0.0f));
  // 64·25² − 8·25 = 39,800 triangles; 1.3 m tall, spout turned towards the "main" camera.
  put(s, make_teapot(25), "reflector", mirror, place({0.0f, 0.0f, 0.0f}, -60.0f, vec3(1.3f)));
  return s;
}

// room-reflector with its cylinder replaced by a car-like mirror body of 39,936 triangles
// (the paper's second reflector is a 39,748-face car): a boxy lower body and a rounder
// cabin, two superellipsoids; no wheels. Mostly convex, so unlike the teapot it reflects
// itself only where the body's top meets the cabin.
Scene make_room_car() {
  Scene s = without_object(make_room_reflector(), "reflector");
  s.name = "room-car";
  const uint32_t mirror = add_material(s, material("car_mirror", vec3(0.9f), 1.0f, 0.0f));
  Mesh car = make_superellipsoid({1.5f, 0.32f, 0.68f}, 0.3f, 160, 100);  // 31,680 triangles
  transform_mesh(car, glm::translate(mat4(1.0f), vec3(0.0f, 0.5f, 0.0f)));
  Mesh cabin = make_superellipsoid({0.8f, 0.3f, 0.58f}, 0.55f, 96, 44);  // 8,256 triangles
  transform_mesh(cabin, glm::translate(mat4(1.0f), vec3(-0.2f, 0.8f, 0.0f)));
  append_mesh(car, cabin);
  put(s, car, "reflector", mirror, place({0.0f, 0.0f, 0.0f}, -30.0f, vec3(1.0f)));
  return s;
}

// The parallax scene of the paper's Fig. 8: the 8 × 8 × 4 m room (1 m checks on the floor
// and the front wall), the mirror cylinder at its center and a red sphere between the
// cylinder and the front wall, off the room's axis; cameras "left" and "right" see the
// sphere's reflection shift against the wall.
Scene make_room_parallax() {
  Scene s;
  s.name = "room-parallax";
  const Material floor = checker_floor(s);
  Material front = material("front_checker", vec3(1.0f));
  front.diffuse_texture = int(add_checker(s, "front_checker", {0.85f, 0.8f, 0.6f}, {0.3f, 0.3f, 0.6f}, 8));
  put_test_room(s, floor, front);
  const uint32_t red = add_material(s, material("red", {0.85f, 0.1f, 0.1f}));
  put(s, make_sphere(0.4f, 48, 24), "sphere", red, place({0.5f, 0.9f, 2.0f}));
  put_reflector_and_lamp(s);
  s.point_lights.push_back({{2.5f, 3.5f, -2.5f}, vec3(8.0f)});
  s.ambient = vec3(0.05f);
  s.cameras.push_back(camera("left", {-1.8f, 1.6f, 3.4f}, {0, 1.0f, 0}, 45.0f));
  s.cameras.push_back(camera("right", {1.8f, 1.6f, 3.4f}, {0, 1.0f, 0}, 45.0f));
  return s;
}

struct Entry {
  const char* name;
  const char* description;
  Scene (*build)();
};

constexpr Entry kScenes[] = {
    {"cornell", "Cornell box with a mirror sphere, a glossy block and an area light", make_cornell},
    {"room-reflector", "8x8x4 m room around a 2,176-triangle mirror cylinder (env-map test scene)",
     make_room_reflector},
    {"living-room", "furnished living room, ~280k triangles, many mirror and glossy reflectors",
     make_living_room},
    {"bathroom", "bathroom with mirror, glossy tiles and chrome fixtures, ~90k triangles",
     make_bathroom},
    {"rooms", "visibility test: 2 rooms joined by a door, 20 polygons", make_vis_rooms},
    {"maze", "visibility test: maze with off-axis walls, ~325 polygons", make_vis_maze},
    {"arena", "visibility test: game arena with blocks and platforms, ~667 polygons", make_vis_arena},
    {"vcity", "visibility test: city of 225 box buildings, 1,126 polygons", make_vis_vcity},
    {"floor", "visibility test: office floor, 60 offices, ~1,750 polygons", make_vis_floor},
    {"building", "visibility test: 5 office floors with a stairwell, ~9,700 polygons (proxima visibility --floors N)",
     [] { return make_vis_building(5); }},
    {"colonnade", "visibility test: thin columns and a railing in front of a textured wall, 57 polygons",
     make_vis_colonnade},
    {"balcony", "visibility test: a dark railing of 61 thin balusters in front of a bright textured facade, 262 polygons",
     make_vis_balcony},
    {"level-small", "visibility test: brush-built game level, 3x3 rooms x 2 storeys, no detail brushes, ~2.7k triangles",
     [] { return make_level(level_options("level-small")); }},
    {"level-medium", "visibility test: brush-built game level, 4x3 rooms x 2 storeys, ~6.1k triangles",
     [] { return make_level(level_options("level-medium")); }},
    {"level-large", "visibility test: brush-built game level, 6x4 rooms x 3 storeys, ~19k triangles",
     [] { return make_level(level_options("level-large")); }},
    {"level-huge", "visibility test: brush-built game level, 8x8 rooms x 3 storeys, ~51k triangles",
     [] { return make_level(level_options("level-huge")); }},
    {"nest", "bird nest of ~5,500 interwoven twigs in a bowl, ~67k triangles (depth-image sampling)", make_nest_scene},
    {"grass", "patch of ~4,600 double-sided grass blades, ~56k triangles (depth-image sampling)",
     [] { return make_grass_scene(); }},
    {"city", "64 x 64 grid of box buildings, ~50k triangles (depth-image sampling)", make_city_scene},
    {"tree", "branching tree with ~25k double-sided leaves, ~113k triangles (depth-image sampling)", make_tree_scene},
    {"room-teapot", "room-reflector with a 39,800-triangle mirror teapot as the reflector", make_room_teapot},
    {"room-car", "room-reflector with a 39,936-triangle car-like mirror body as the reflector", make_room_car},
    {"room-parallax", "8x8x4 m room, mirror cylinder and a sphere in front of a checkered wall (parallax)",
     make_room_parallax},
};

}  // namespace

std::vector<BuiltinSceneInfo> builtin_scenes() {
  std::vector<BuiltinSceneInfo> out;
  for (const Entry& e : kScenes) out.push_back({e.name, e.description});
  return out;
}

bool is_builtin_scene(const std::string& name) {
  return std::any_of(std::begin(kScenes), std::end(kScenes),
                     [&](const Entry& e) { return name == e.name; });
}

Scene make_builtin_scene(const std::string& name) {
  for (const Entry& e : kScenes) {
    if (name == e.name) return e.build();
  }
  std::string known;
  for (const Entry& e : kScenes) known += std::string(known.empty() ? "" : ", ") + e.name;
  fail_input("unknown built-in scene '" + name + "' (known: " + known + ")");
}

}  // namespace proxima
