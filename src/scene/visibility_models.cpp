// Test models for exact visibility maps, after Figure 7 of Funkhouser's visibility paper
// (rooms, maze, arena, city, one floor of Soda Hall, five floors of Soda Hall). The
// originals are not public; these are procedural stand-ins of the same kind and size.
#include "proxima/scene/visibility_models.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/error.h"
#include "proxima/core/range_check.h"
#include "proxima/core/rng.h"
#include "proxima/scene/level_scenes.h"
#include "proxima/scene/procedural.h"

namespace proxima {
namespace {

uint32_t add_gray(Scene& s, const std::string& name, vec3 color) {
  Material m;
  m.name = name;
  m.diffuse = color;
  return add_material(s, m);
}

// One quad corner, corner + u, corner + u + v, corner + v, facing cross(u, v).
void quad(Scene& s, vec3 corner, vec3 u, vec3 v, uint32_t mat, const std::string& name) {
  Mesh m;
  m.positions = {corner, corner + u, corner + u + v, corner + v};
  vec3 n = glm::normalize(glm::cross(u, v));
  m.normals.assign(4, n);
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  add_object(s, m, name, mat);
}

// Vertical quad from a to b (floor points), from height y0 to y1.
void wall(Scene& s, vec3 a, vec3 b, float y0, float y1, uint32_t mat, const std::string& name) {
  quad(s, {a.x, y0, a.z}, {b.x - a.x, 0, b.z - a.z}, {0, y1 - y0, 0}, mat, name);
}

// Box of the given size standing on `base`, rotated yaw degrees about +Y; without its
// bottom face unless `bottom` (5 or 6 polygons).
void box(Scene& s, vec3 base, vec3 size, float yaw_deg, uint32_t mat, const std::string& name,
         bool bottom = false) {
  Mesh m = make_box(size, 1);
  if (!bottom) {
    // make_box faces are 4 vertices / 2 triangles each; drop the one facing −Y.
    Mesh kept;
    for (size_t t = 0; t < m.triangles.size(); t += 2) {
      if (m.normals[m.triangles[t][0]].y < -0.5f) continue;
      uint32_t base_index = uint32_t(kept.positions.size());
      std::vector<uint32_t> remap;
      for (int k = 0; k < 2; ++k) {
        uvec3 tri = m.triangles[t + size_t(k)];
        uvec3 out;
        for (int j = 0; j < 3; ++j) {
          auto it = std::find(remap.begin(), remap.end(), tri[j]);
          if (it == remap.end()) {
            remap.push_back(tri[j]);
            kept.positions.push_back(m.positions[tri[j]]);
            kept.normals.push_back(m.normals[tri[j]]);
            kept.uvs.push_back(m.uvs[tri[j]]);
            out[j] = base_index + uint32_t(remap.size() - 1);
          } else {
            out[j] = base_index + uint32_t(it - remap.begin());
          }
        }
        kept.triangles.push_back(out);
      }
    }
    m = std::move(kept);
  }
  mat4 t = glm::translate(mat4(1.0f), base + vec3(0, 0.5f * size.y, 0));
  t = glm::rotate(t, glm::radians(yaw_deg), vec3(0, 1, 0));
  transform_mesh(m, t);
  add_object(s, m, name, mat);
}

// A path through `points` (one key per point, 1 s apart) looking `ahead` points forward.
// A named camera at the start of the scene's walk, so every built-in scene can be rendered
// with --camera and checked from a camera (raster agreement, render tests).
void add_walk_start_camera(Scene& s) {
  const CameraPath& path = s.camera_paths.front();
  s.cameras.push_back({"walk_start", camera_at_time(path, frame_time(path, 0), 512, 512, 0.01f, 1000.0f)});
}

CameraPath walk_through(const std::vector<vec3>& points, int frames, float fov = 70.0f,
                        int ahead = 1, vec3 look_offset = vec3(0.0f)) {
  CameraPath p;
  p.name = "walk";
  p.frames = frames;
  for (size_t i = 0; i < points.size(); ++i) {
    size_t j = std::min(points.size() - 1, i + size_t(ahead));
    vec3 target = j > i ? points[j] : points[i] + (points[i] - points[i - 1]);
    p.keys.push_back({float(i), points[i], target + look_offset, fov});
  }
  return p;
}

void lights(Scene& s, vec3 at) {
  PointLight l;
  l.position = at;
  l.intensity = vec3(40.0f);
  s.point_lights.push_back(l);
  s.ambient = vec3(0.25f);
}

// ---- office floor (floor and building) ---------------------------------------------
constexpr float kStorey = 3.2f;     // floor-to-floor height
constexpr float kCeiling = 3.0f;    // room height
constexpr float kOffice = 4.0f;     // office width along x
constexpr float kDepth = 20.0f;     // floor depth along z
constexpr float kCorridor0 = 8.5f, kCorridor1 = 11.5f;
// Stairwell opening in the south office 0.
constexpr float kHoleX0 = 0.5f, kHoleX1 = 3.5f, kHoleZ0 = 1.0f, kHoleZ1 = 7.0f;

// Horizontal rectangle [x0,x1] × [z0,z1] at height y facing up or down, minus the stair
// hole when `hole` (then as 4 quads around it).
void slab(Scene& s, float x1, float y, bool up, bool hole, uint32_t mat, const std::string& name) {
  auto rect = [&](float a0, float a1, float b0, float b1) {
    if (up) quad(s, {a0, y, b1}, {a1 - a0, 0, 0}, {0, 0, b0 - b1}, mat, name);
    else quad(s, {a0, y, b0}, {a1 - a0, 0, 0}, {0, 0, b1 - b0}, mat, name);
  };
  if (!hole) {
    rect(0, x1, 0, kDepth);
    return;
  }
  rect(0, x1, 0, kHoleZ0);
  rect(0, x1, kHoleZ1, kDepth);
  rect(0, kHoleX0, kHoleZ0, kHoleZ1);
  rect(kHoleX1, x1, kHoleZ0, kHoleZ1);
}

void office_floor(Scene& s, int level, int offices_per_side, bool hole_below, bool stairs_up,
                  uint64_t seed) {
  const float y0 = float(level) * kStorey;
  const float length = float(offices_per_side) * kOffice;
  const uint32_t floor_mat = add_gray(s, "floor_" + std::to_string(level), {0.5f, 0.45f, 0.4f});
  const uint32_t wall_mat = add_gray(s, "wall_" + std::to_string(level), {0.8f, 0.8f, 0.75f});
  const uint32_t furn = add_gray(s, "furniture_" + std::to_string(level), {0.45f, 0.3f, 0.2f});
  const std::string L = "f" + std::to_string(level) + "_";
  slab(s, length, y0, true, hole_below, floor_mat, L + "floor");
  slab(s, length, y0 + kCeiling, false, stairs_up, wall_mat, L + "ceiling");
  if (stairs_up) {
    // The slab edge around the hole, between this ceiling and the next floor.
    const float a = y0 + kCeiling, b = y0 + kStorey;
    wall(s, {kHoleX0, 0, kHoleZ0}, {kHoleX1, 0, kHoleZ0}, a, b, wall_mat, L + "hole_s");
    wall(s, {kHoleX1, 0, kHoleZ1}, {kHoleX0, 0, kHoleZ1}, a, b, wall_mat, L + "hole_n");
    wall(s, {kHoleX0, 0, kHoleZ1}, {kHoleX0, 0, kHoleZ0}, a, b, wall_mat, L + "hole_w");
    wall(s, {kHoleX1, 0, kHoleZ0}, {kHoleX1, 0, kHoleZ1}, a, b, wall_mat, L + "hole_e");
    for (int k = 0; k < 12; ++k) {
      const float h = float(k + 1) * kStorey / 12.0f;
      box(s, {2.0f, y0, kHoleZ0 + 0.25f + 0.5f * float(k)}, {2.6f, h, 0.5f}, 0.0f, furn,
          L + "step_" + std::to_string(k));
    }
  }
  // Outer walls.
  wall(s, {0, 0, 0}, {length, 0, 0}, y0, y0 + kCeiling, wall_mat, L + "outer_s");
  wall(s, {length, 0, kDepth}, {0, 0, kDepth}, y0, y0 + kCeiling, wall_mat, L + "outer_n");
  wall(s, {0, 0, kDepth}, {0, 0, 0}, y0, y0 + kCeiling, wall_mat, L + "outer_w");
  wall(s, {length, 0, 0}, {length, 0, kDepth}, y0, y0 + kCeiling, wall_mat, L + "outer_e");
  Pcg32 rng(seed, uint64_t(level) + 1);
  auto uniform = [&](float a, float b) { return a + (b - a) * rng.next_float(); };
  for (int side = 0; side < 2; ++side) {
    const float zc = side == 0 ? kCorridor0 : kCorridor1;       // corridor wall
    const float zin = side == 0 ? 0.5f * kCorridor0 : 0.5f * (kCorridor1 + kDepth);
    for (int i = 0; i < offices_per_side; ++i) {
      const float x0 = float(i) * kOffice;
      const std::string o = L + (side ? "n" : "s") + std::to_string(i) + "_";
      // Door wall: two pieces and a lintel over a 1 m × 2.1 m door.
      wall(s, {x0, 0, zc}, {x0 + 1.5f, 0, zc}, y0, y0 + kCeiling, wall_mat, o + "wall_a");
      wall(s, {x0 + 2.5f, 0, zc}, {x0 + kOffice, 0, zc}, y0, y0 + kCeiling, wall_mat, o + "wall_b");
      wall(s, {x0 + 1.5f, 0, zc}, {x0 + 2.5f, 0, zc}, y0 + 2.1f, y0 + kCeiling, wall_mat, o + "lintel");
      if (i > 0) {
        const float za = side == 0 ? 0.0f : kCorridor1, zb = side == 0 ? kCorridor0 : kDepth;
        wall(s, {x0, 0, za}, {x0, 0, zb}, y0, y0 + kCeiling, wall_mat, o + "partition");
      }
      if (stairs_up && side == 0 && i == 0) continue;  // the stairwell office
      if (hole_below && side == 0 && i == 0) continue;
      const float far_z = side == 0 ? 1.2f : kDepth - 1.2f;
      box(s, {x0 + uniform(1.2f, 2.8f), y0, far_z}, {1.6f, 0.75f, 0.8f}, uniform(-10, 10), furn, o + "desk");
      box(s, {x0 + uniform(1.2f, 2.8f), y0, zin + uniform(-0.8f, 0.2f)}, {0.5f, 1.0f, 0.5f},
          uniform(0, 90), furn, o + "chair");
      box(s, {x0 + 0.45f, y0, zin + uniform(-1.0f, 1.0f)}, {0.5f, 1.3f, 1.0f}, 0.0f, furn, o + "cabinet");
      box(s, {x0 + kOffice - 0.35f, y0, zin + uniform(-1.5f, 1.5f)}, {0.4f, 2.0f, 1.2f}, 0.0f, furn,
          o + "shelf");
      box(s, {x0 + uniform(1.0f, 3.0f), y0, zin + uniform(0.5f, 1.5f) * (side ? -1.0f : 1.0f)},
          {0.4f, uniform(0.4f, 1.5f), 0.4f}, uniform(0, 90), furn, o + "plant");
    }
  }
}

// The ground-floor walk: along the corridor, into office s3 and n6 and back out.
CameraPath office_walk(int offices_per_side) {
  const float length = float(offices_per_side) * kOffice;
  const float y = 1.6f, zc = 0.5f * (kCorridor0 + kCorridor1);
  std::vector<vec3> pts;
  pts.push_back({1.0f, y, zc});
  for (float x = 4.0f; x < 14.0f; x += 3.0f) pts.push_back({x, y, zc});
  pts.push_back({14.0f, y, kCorridor0 + 0.6f});   // door of office s3 (x 12..16)
  pts.push_back({14.0f, y, 5.0f});
  pts.push_back({14.0f, y, 3.0f});
  pts.push_back({13.5f, y, 5.5f});
  pts.push_back({14.0f, y, kCorridor0 + 0.6f});
  for (float x = 17.0f; x < 26.0f; x += 3.0f) pts.push_back({x, y, zc});
  pts.push_back({26.0f, y, kCorridor1 - 0.6f});   // door of office n6 (x 24..28)
  pts.push_back({26.0f, y, 15.0f});
  pts.push_back({26.5f, y, 17.0f});
  pts.push_back({26.0f, y, kCorridor1 - 0.6f});
  for (float x = 29.0f; x < std::min(length - 2.0f, 60.0f); x += 3.0f) pts.push_back({x, y, zc});
  return walk_through(pts, 150, 70.0f, 1);
}

}  // namespace

Scene make_vis_rooms() {
  Scene s;
  s.name = "rooms";
  const uint32_t ma = add_gray(s, "room_a", {0.8f, 0.75f, 0.6f});
  const uint32_t mb = add_gray(s, "room_b", {0.55f, 0.65f, 0.8f});
  const uint32_t md = add_gray(s, "door_frame", {0.5f, 0.35f, 0.25f});
  // Room A: x 0..5, room B: x 5.2..9, z 0..4; the wall between is x 5..5.2 with a door
  // z 1.5..2.5, 2.1 m high.
  const float h = 3.0f, dz0 = 1.5f, dz1 = 2.5f, dh = 2.1f;
  quad(s, {0, 0, 4}, {5, 0, 0}, {0, 0, -4}, ma, "a_floor");
  quad(s, {0, h, 0}, {5, 0, 0}, {0, 0, 4}, ma, "a_ceiling");
  wall(s, {0, 0, 0}, {5, 0, 0}, 0, h, ma, "a_back");
  wall(s, {5, 0, 4}, {0, 0, 4}, 0, h, ma, "a_front");
  wall(s, {0, 0, 4}, {0, 0, 0}, 0, h, ma, "a_left");
  wall(s, {5, 0, 0}, {5, 0, dz0}, 0, h, ma, "a_door_wall_1");
  wall(s, {5, 0, dz1}, {5, 0, 4}, 0, h, ma, "a_door_wall_2");
  wall(s, {5, 0, dz0}, {5, 0, dz1}, dh, h, ma, "a_lintel");
  wall(s, {5.2f, 0, dz0}, {5.2f, 0, 0}, 0, h, mb, "b_door_wall_1");
  wall(s, {5.2f, 0, 4}, {5.2f, 0, dz1}, 0, h, mb, "b_door_wall_2");
  wall(s, {5.2f, 0, dz1}, {5.2f, 0, dz0}, dh, h, mb, "b_lintel");
  wall(s, {5, 0, dz0}, {5.2f, 0, dz0}, 0, dh, md, "jamb_1");
  wall(s, {5.2f, 0, dz1}, {5, 0, dz1}, 0, dh, md, "jamb_2");
  quad(s, {5, dh, dz0}, {0.2f, 0, 0}, {0, 0, dz1 - dz0}, md, "door_head");
  quad(s, {5, 0, dz1}, {0.2f, 0, 0}, {0, 0, dz0 - dz1}, md, "threshold");
  quad(s, {5.2f, 0, 4}, {3.8f, 0, 0}, {0, 0, -4}, mb, "b_floor");
  quad(s, {5.2f, h, 0}, {3.8f, 0, 0}, {0, 0, 4}, mb, "b_ceiling");
  wall(s, {5.2f, 0, 0}, {9, 0, 0}, 0, h, mb, "b_back");
  wall(s, {9, 0, 4}, {5.2f, 0, 4}, 0, h, mb, "b_front");
  wall(s, {9, 0, 0}, {9, 0, 4}, 0, h, mb, "b_right");
  lights(s, {2.5f, 2.8f, 2.0f});
  s.camera_paths.push_back(walk_through({{0.8f, 1.6f, 0.8f}, {2.5f, 1.6f, 1.2f}, {3.8f, 1.6f, 2.0f},
                                          {4.7f, 1.6f, 2.0f}, {5.6f, 1.6f, 2.0f}, {7.2f, 1.6f, 2.6f},
                                          {8.2f, 1.6f, 1.6f}, {7.0f, 1.6f, 0.8f}, {5.8f, 1.6f, 1.8f},
                                          {4.6f, 1.6f, 2.1f}, {2.5f, 1.6f, 3.2f}, {1.0f, 1.6f, 2.0f}},
                                         120, 70.0f, 1));
  add_walk_start_camera(s);
  return s;
}

Scene make_vis_maze() {
  Scene s;
  s.name = "maze";
  const uint32_t wall_mat = add_gray(s, "hedge", {0.35f, 0.6f, 0.3f});
  const uint32_t ground = add_gray(s, "ground", {0.6f, 0.55f, 0.45f});
  constexpr int n = 17;
  constexpr float cell = 2.0f, height = 2.5f;
  Pcg32 rng(7, 3);
  // Jittered corner grid, rotated 25° about +Y around the maze center.
  const float c = std::cos(glm::radians(25.0f)), sn = std::sin(glm::radians(25.0f));
  const float half = 0.5f * float(n) * cell;
  std::vector<vec3> corner((n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      float jx = (i > 0 && i < n) ? 0.7f * (rng.next_float() - 0.5f) : 0.0f;
      float jz = (j > 0 && j < n) ? 0.7f * (rng.next_float() - 0.5f) : 0.0f;
      float x = float(i) * cell - half + jx, z = float(j) * cell - half + jz;
      corner[size_t(j * (n + 1) + i)] = {c * x + sn * z, 0.0f, -sn * x + c * z};
    }
  auto at = [&](int i, int j) { return corner[size_t(j * (n + 1) + i)]; };
  // Perfect maze by randomized depth-first search; open[cell][dir] (0 +x, 1 +z, 2 −x, 3 −z).
  std::vector<std::array<bool, 4>> open(n * n, {false, false, false, false});
  std::vector<bool> seen(n * n, false);
  std::vector<int> parent(n * n, -1), stack = {0};
  seen[0] = true;
  const int di[4] = {1, 0, -1, 0}, dj[4] = {0, 1, 0, -1};
  while (!stack.empty()) {
    int cur = stack.back(), ci = cur % n, cj = cur / n;
    int options[4], count = 0;
    for (int d = 0; d < 4; ++d) {
      int ni = ci + di[d], nj = cj + dj[d];
      if (ni >= 0 && ni < n && nj >= 0 && nj < n && !seen[size_t(nj * n + ni)]) options[count++] = d;
    }
    if (count == 0) {
      stack.pop_back();
      continue;
    }
    int d = options[rng.next_u32() % uint32_t(count)];
    int next = (cj + dj[d]) * n + ci + di[d];
    open[size_t(cur)][size_t(d)] = true;
    open[size_t(next)][size_t((d + 2) % 4)] = true;
    seen[size_t(next)] = true;
    parent[size_t(next)] = cur;
    stack.push_back(next);
  }
  int walls = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool entrance = i == 0 && j == 0, exit = i == n - 1 && j == n - 1;
      // +z side (the exit opens the last cell's), +x side, and the −z / −x borders.
      if (!open[size_t(j * n + i)][1] && !exit)
        wall(s, at(i + 1, j + 1), at(i, j + 1), 0, height, wall_mat, "wall_" + std::to_string(walls++));
      if (!open[size_t(j * n + i)][0])
        wall(s, at(i + 1, j), at(i + 1, j + 1), 0, height, wall_mat, "wall_" + std::to_string(walls++));
      if (j == 0 && !entrance) wall(s, at(i, 0), at(i + 1, 0), 0, height, wall_mat, "wall_" + std::to_string(walls++));
      if (i == 0) wall(s, at(0, j + 1), at(0, j), 0, height, wall_mat, "wall_" + std::to_string(walls++));
    }
  const float g = half + 4.0f;
  quad(s, {-g, 0, g}, {2 * g, 0, 0}, {0, 0, -2 * g}, ground, "ground");
  lights(s, {0, 20, 0});
  // The path: the solution from the entrance cell (0, 0) to the exit cell, through the
  // jittered cell centers, starting outside the entrance and ending outside the exit.
  auto center = [&](int id) {
    int i = id % n, j = id / n;
    return 0.25f * (at(i, j) + at(i + 1, j) + at(i, j + 1) + at(i + 1, j + 1)) + vec3(0, 1.6f, 0);
  };
  std::vector<vec3> pts;
  for (int id = n * n - 1; id >= 0; id = parent[size_t(id)]) pts.push_back(center(id));
  std::reverse(pts.begin(), pts.end());
  pts.insert(pts.begin(), center(0) + (center(0) - center(n)));  // outside, before the entrance
  s.camera_paths.push_back(walk_through(pts, std::max(120, int(pts.size()) * 3), 70.0f, 1));
  add_walk_start_camera(s);
  return s;
}

Scene make_vis_arena() {
  Scene s;
  s.name = "arena";
  const uint32_t floor_mat = add_gray(s, "arena_floor", {0.4f, 0.4f, 0.45f});
  const uint32_t wall_mat = add_gray(s, "arena_wall", {0.6f, 0.5f, 0.45f});
  const uint32_t block = add_gray(s, "block", {0.7f, 0.6f, 0.3f});
  const float r = 20.0f, h = 6.0f;
  quad(s, {-r, 0, r}, {2 * r, 0, 0}, {0, 0, -2 * r}, floor_mat, "floor");
  wall(s, {-r, 0, -r}, {r, 0, -r}, 0, h, wall_mat, "wall_n");
  wall(s, {r, 0, r}, {-r, 0, r}, 0, h, wall_mat, "wall_s");
  wall(s, {-r, 0, r}, {-r, 0, -r}, 0, h, wall_mat, "wall_w");
  wall(s, {r, 0, -r}, {r, 0, r}, 0, h, wall_mat, "wall_e");
  Pcg32 rng(11, 5);
  auto uniform = [&](float a, float b) { return a + (b - a) * rng.next_float(); };
  // 130 blocks, kept off the ring 10.5 m .. 16.5 m from the center the path follows.
  for (int k = 0; k < 130;) {
    vec3 p{uniform(-18, 18), 0, uniform(-18, 18)};
    float d = glm::length(vec2(p.x, p.z));
    if (d > 10.5f && d < 16.5f) continue;
    box(s, p, {uniform(0.6f, 2.5f), uniform(0.5f, 5.0f), uniform(0.6f, 2.5f)}, uniform(0, 90), block,
        "block_" + std::to_string(k));
    ++k;
  }
  box(s, {-5, 3.0f, 0}, {6, 0.3f, 3}, 15.0f, block, "platform_a", true);
  box(s, {5, 2.0f, 4}, {4, 0.3f, 4}, -30.0f, block, "platform_b", true);
  lights(s, {0, 5.5f, 0});
  std::vector<vec3> pts;
  for (int k = 0; k <= 24; ++k) {
    float phi = 2.0f * kPi * float(k) / 24.0f;
    pts.push_back({13.5f * std::sin(phi), 1.7f, 13.5f * std::cos(phi)});
  }
  s.camera_paths.push_back(walk_through(pts, 150, 70.0f, 2));
  add_walk_start_camera(s);
  return s;
}

Scene make_vis_vcity() {
  Scene s;
  s.name = "vcity";
  const uint32_t ground = add_gray(s, "ground", {0.35f, 0.35f, 0.35f});
  const uint32_t house = add_gray(s, "building", {0.75f, 0.7f, 0.6f});
  constexpr int n = 15;
  constexpr float pitch = 12.0f;
  const float half = 0.5f * float(n) * pitch;
  Pcg32 rng(13, 9);
  auto uniform = [&](float a, float b) { return a + (b - a) * rng.next_float(); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      vec3 c{(float(i) + 0.5f) * pitch - half, 0, (float(j) + 0.5f) * pitch - half};
      box(s, c, {uniform(6, 10), uniform(5, 30), uniform(6, 10)}, 0.0f, house,
          "building_" + std::to_string(j * n + i));
    }
  quad(s, {-half - 10, 0, half + 10}, {2 * half + 20, 0, 0}, {0, 0, -2 * half - 20}, ground, "ground");
  lights(s, {0, 100, 0});
  // Streets run along x = k·pitch − half and z = k·pitch − half; fly a zig-zag over them.
  std::vector<vec3> pts;
  const float y = 8.0f;
  auto street = [&](int k) { return float(k) * pitch - half; };
  for (int leg = 0; leg < 4; ++leg) {
    const float z = street(2 + 3 * leg);
    for (int k = 1; k <= 13; k += 2) {
      int kk = leg % 2 == 0 ? k : 14 - k;
      pts.push_back({street(kk), y, z});
    }
    pts.push_back({street(leg % 2 == 0 ? 14 : 0), y, z + 1.5f * pitch});
  }
  s.camera_paths.push_back(walk_through(pts, 160, 65.0f, 2, vec3(0, -3.0f, 0)));
  add_walk_start_camera(s);
  return s;
}

Scene make_vis_floor() {
  Scene s;
  s.name = "floor";
  office_floor(s, 0, 30, false, false, 17);
  lights(s, {60, 2.8f, 10});
  s.camera_paths.push_back(office_walk(30));
  add_walk_start_camera(s);
  return s;
}

Scene make_vis_building(int floors) {
  require_in_range(floors, 1, 64, "--floors", "(got " + std::to_string(floors) + ")");
  Scene s;
  s.name = floors == 5 ? "building" : "building:" + std::to_string(floors);
  for (int level = 0; level < floors; ++level)
    office_floor(s, level, 32, level > 0, level + 1 < floors, 19);
  lights(s, {64, 2.8f, 10});
  s.camera_paths.push_back(office_walk(32));
  add_walk_start_camera(s);
  return s;
}

Scene make_vis_colonnade() {
  Scene s;
  s.name = "colonnade";
  const uint32_t room = add_gray(s, "room", {0.8f, 0.75f, 0.6f});
  const uint32_t stone = add_gray(s, "columns", {0.45f, 0.5f, 0.6f});
  const uint32_t rail = add_gray(s, "railing", {0.3f, 0.25f, 0.2f});
  // A room x 0..8, z 0..4, 3 m high; the textured back wall (z = 0) seen through a row of
  // 12 cm columns (z = 1.4, every 0.8 m) and a 6 cm railing bar in front of them (z = 1.0).
  const float h = 3.0f, L = 8.0f, D = 4.0f;
  quad(s, {0, 0, D}, {L, 0, 0}, {0, 0, -D}, room, "floor");
  quad(s, {0, h, 0}, {L, 0, 0}, {0, 0, D}, room, "ceiling");
  wall(s, {0, 0, 0}, {L, 0, 0}, 0, h, room, "back");
  wall(s, {L, 0, D}, {0, 0, D}, 0, h, room, "front");
  wall(s, {0, 0, D}, {0, 0, 0}, 0, h, room, "left");
  wall(s, {L, 0, 0}, {L, 0, D}, 0, h, room, "right");
  for (int i = 0; i < 9; ++i)
    box(s, {0.8f * float(i + 1), 0, 1.4f}, {0.12f, 2.6f, 0.12f}, 0.0f, stone, "column_" + std::to_string(i));
  box(s, {4.0f, 0.9f, 1.0f}, {7.4f, 0.06f, 0.06f}, 0.0f, rail, "railing", true);
  lights(s, {4.0f, 2.8f, 3.0f});
  // Along the room, 2.2 m from the columns, looking at the back wall and ahead.
  std::vector<vec3> pts;
  for (int i = 0; i <= 6; ++i) pts.push_back({0.8f + 1.05f * float(i), 1.5f, 3.4f});
  s.camera_paths.push_back(walk_through(pts, 120, 65.0f, 1, vec3(0, -0.2f, -3.0f)));
  add_walk_start_camera(s);
  return s;
}

bool is_visibility_model(const std::string& name) {
  for (const char* m : {"rooms", "maze", "arena", "vcity", "floor", "building", "colonnade", "balcony"})
    if (name == m) return true;
  return name.rfind("building:", 0) == 0 || is_level_scene(name);
}

}  // namespace proxima
