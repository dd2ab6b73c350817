// Brush-built game levels: convex brushes placed the way a level editor places them, with no
// CSG between them (see level_scenes.h for the defect classes and the layout).
#include "proxima/scene/level_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/range_check.h"
#include "proxima/core/rng.h"

namespace proxima {
namespace {

constexpr float kRoomX = 8.0f;     // room pitch along x (wall center line to center line)
constexpr float kRoomZ = 7.0f;     // room pitch along z
constexpr float kStorey = 3.5f;    // floor-to-floor height
constexpr float kSlab = 0.25f;     // slab thickness (top = the floor)
constexpr float kWall = 0.2f;      // wall thickness, centered on the grid lines
constexpr float kDoorW = 1.2f, kDoorH = 2.4f;
constexpr float kBand = 1.25f;     // half width of the ramp / stair band (and its slab hole)
constexpr float kCross = 1.3f;     // half width of the free cross between a room's doors
constexpr float kEye = 1.6f;       // eye height above the floor
constexpr int kSteps = 14;

// A convex brush: vertices and faces (vertex loops, counter-clockwise seen from outside).
struct Brush {
  std::vector<vec3> v;
  std::vector<std::vector<int>> faces;
};

// Face order of box brushes (bits for `drop` masks).
enum BoxFace { kNegX = 1, kPosX = 2, kNegY = 4, kPosY = 8, kNegZ = 16, kPosZ = 32 };

vec3 yaw_about(vec3 p, vec3 pivot, float yaw_rad) {
  if (yaw_rad == 0.0f) return p;
  const float c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  const vec3 d = p - pivot;
  return pivot + vec3(d.x * c + d.z * s, d.y, -d.x * s + d.z * c);
}

class LevelBuilder {
 public:
  LevelBuilder(Scene& scene, const LevelOptions& o) : s_(scene), o_(o), rng_(o.seed, 0x1e7e1) {}

  float uniform(float a, float b) { return a + (b - a) * rng_.next_float(); }
  bool chance(float p) { return rng_.next_float() < p; }
  int pick(int n) { return int(rng_.next_below(uint32_t(n))); }

  // A seam coordinate: moved by ±seam_jitter with probability 1/4 (a gap or an overlap).
  float seam(float v) {
    const uint32_t r = rng_.next_below(8);
    if (r == 0) return v + o_.seam_jitter;
    if (r == 1) return v - o_.seam_jitter;
    return v;
  }

  // Axis-aligned box [lo, hi], then turned yaw radians about its vertical center axis. Its
  // corners come from lo/hi or from center ± half size (one ulp apart in float), at random.
  Brush box(vec3 lo, vec3 hi, float yaw = 0.0f) {
    Brush b;
    const bool from_center = chance(0.5f);
    const vec3 c = 0.5f * (lo + hi), h = 0.5f * (hi - lo);
    for (int k = 0; k < 8; ++k) {
      const vec3 sgn((k & 1) ? 1.0f : -1.0f, (k & 2) ? 1.0f : -1.0f, (k & 4) ? 1.0f : -1.0f);
      vec3 p = from_center ? c + sgn * h : Bounds3{lo, hi}.corner(k);
      b.v.push_back(yaw_about(p, c, yaw));
    }
    b.faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    return b;
  }

  // Wedge (ramp) in the box [lo, hi] rising from lo.y at x = lo.x to hi.y at x = hi.x, then
  // turned yaw radians about its vertical center axis.
  Brush wedge(vec3 lo, vec3 hi, float yaw = 0.0f) {
    Brush b;
    const vec3 c = 0.5f * (lo + hi);
    b.v = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
           {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}};
    for (vec3& p : b.v) p = yaw_about(p, c, yaw);
    b.faces = {{0, 1, 4, 3}, {1, 2, 5, 4}, {0, 3, 5, 2}, {0, 2, 1}, {3, 4, 5}};
    return b;
  }

  // n-sided prism of circumradius r around (center.x, center.z) from y0 to y1.
  Brush prism(vec3 center, float r, float y0, float y1, int n, float yaw) {
    Brush b;
    for (int i = 0; i < n; ++i) {
      const float a = yaw + 2.0f * kPi * float(i) / float(n);
      b.v.push_back({center.x + r * std::cos(a), y0, center.z + r * std::sin(a)});
    }
    for (int i = 0; i < n; ++i) b.v.push_back(b.v[size_t(i)] + vec3(0, y1 - y0, 0));
    std::vector<int> bottom, top;
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      b.faces.push_back({i, n + i, n + j, j});
      bottom.push_back(i);
      top.push_back(2 * n - 1 - i);
    }
    b.faces.push_back(bottom);
    b.faces.push_back(top);
    return b;
  }

  // Emits the brush as one object: each face its own vertices (flat normal, planar uvs),
  // fan-triangulated; faces whose bit is set in `drop` are left out (an open mesh).
  void emit(const Brush& b, uint32_t mat, const std::string& name, uint32_t drop = 0) {
    Mesh m;
    for (size_t f = 0; f < b.faces.size(); ++f) {
      if (f < 32 && (drop >> f) & 1u) continue;
      const std::vector<int>& loop = b.faces[f];
      vec3 n(0.0f);
      for (size_t i = 0; i < loop.size(); ++i)
        n += glm::cross(b.v[size_t(loop[i])], b.v[size_t(loop[(i + 1) % loop.size()])]);
      n = glm::normalize(n);
      const vec3 an = glm::abs(n);
      const int ax = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
      const uint32_t base = uint32_t(m.positions.size());
      for (int idx : loop) {
        const vec3 p = b.v[size_t(idx)];
        m.positions.push_back(p);
        m.normals.push_back(n);
        m.uvs.push_back(ax == 0 ? vec2(p.z, p.y) : ax == 1 ? vec2(p.x, p.z) : vec2(p.x, p.y));
      }
      for (size_t k = 1; k + 1 < loop.size(); ++k)
        m.triangles.push_back({base, base + uint32_t(k), base + uint32_t(k + 1)});
    }
    if (m.triangles.empty()) return;
    add_object(s_, m, "b" + std::to_string(brushes_++) + "_" + name, mat);
  }

  // Single-sided quad (a decal): corner, corner + u, corner + u + v, corner + v.
  void quad(vec3 corner, vec3 u, vec3 v, uint32_t mat, const std::string& name) {
    Brush b;
    b.v = {corner, corner + u, corner + u + v, corner + v};
    b.faces = {{0, 1, 2, 3}};
    emit(b, mat, name);
  }

 private:
  Scene& s_;
  const LevelOptions& o_;
  Pcg32 rng_;
  int brushes_ = 0;
};

struct Room {
  int i, j;
  bool operator==(const Room&) const = default;
};

struct Layout {
  int nx = 0, nz = 0, floors = 0;
  // doors[f][k]: door between room k = i + j·nx and its +x (dir 0) or +z (dir 1) neighbor.
  std::vector<std::vector<std::array<bool, 2>>> doors;
  // Spanning-tree children of each room per storey (the walk follows tree doors only).
  std::vector<std::vector<std::vector<int>>> children;

  int id(Room r) const { return r.i + r.j * nx; }
  Room room(int k) const { return {k % nx, k / nx}; }
  // The room in which the ramp or stairs climb from storey f to f + 1 (none on the top storey).
  Room rise(int f) const { return f % 2 == 0 ? Room{1, 0} : Room{1, nz - 1}; }
  bool is_rise(int f, Room r) const { return f + 1 < floors && r == rise(f); }
  bool is_landing(int f, Room r) const { return f >= 1 && r == rise(f - 1); }
  bool has_door(int f, Room a, Room b) const {
    if (b.i < a.i || b.j < a.j) std::swap(a, b);
    return doors[size_t(f)][size_t(id(a))][b.i > a.i ? 0 : 1];
  }
};

float x0_of(Room r) { return float(r.i) * kRoomX; }
float z0_of(Room r) { return float(r.j) * kRoomZ; }
vec3 center_of(Room r, int f) {
  return {x0_of(r) + 0.5f * kRoomX, float(f) * kStorey, z0_of(r) + 0.5f * kRoomZ};
}

// Doors per storey: the rise room opens only to its −x neighbor, the landing room only to
// its +x neighbor; the other rooms are joined by a random depth-first spanning tree from
// room (0, 0) plus extra doors with probability 0.2.
Layout plan(const LevelOptions& o, Pcg32& rng) {
  Layout L;
  L.nx = o.rooms_x;
  L.nz = o.rooms_z;
  L.floors = o.floors;
  const int n = L.nx * L.nz;
  L.doors.assign(size_t(L.floors), std::vector<std::array<bool, 2>>(size_t(n), {false, false}));
  L.children.assign(size_t(L.floors), std::vector<std::vector<int>>(size_t(n)));
  auto set_door = [&](int f, Room a, Room b) {
    if (b.i < a.i || b.j < a.j) std::swap(a, b);
    L.doors[size_t(f)][size_t(L.id(a))][b.i > a.i ? 0 : 1] = true;
  };
  for (int f = 0; f < L.floors; ++f) {
    auto special = [&](Room r) { return L.is_rise(f, r) || L.is_landing(f, r); };
    std::vector<bool> seen(size_t(n), false);
    std::vector<int> stack = {0};
    seen[0] = true;
    const int di[4] = {1, 0, -1, 0}, dj[4] = {0, 1, 0, -1};
    while (!stack.empty()) {
      const Room cur = L.room(stack.back());
      int options[4], count = 0;
      for (int d = 0; d < 4; ++d) {
        const Room nb{cur.i + di[d], cur.j + dj[d]};
        if (nb.i < 0 || nb.i >= L.nx || nb.j < 0 || nb.j >= L.nz) continue;
        if (seen[size_t(L.id(nb))] || special(nb)) continue;
        options[count++] = d;
      }
      if (count == 0) {
        stack.pop_back();
        continue;
      }
      const int d = options[rng.next_below(uint32_t(count))];
      const Room nb{cur.i + di[d], cur.j + dj[d]};
      set_door(f, cur, nb);
      L.children[size_t(f)][size_t(L.id(cur))].push_back(L.id(nb));
      seen[size_t(L.id(nb))] = true;
      stack.push_back(L.id(nb));
    }
    for (int k = 0; k < n; ++k) {
      const Room r = L.room(k);
      if (special(r)) continue;
      if (r.i + 1 < L.nx && !special({r.i + 1, r.j}) && rng.next_float() < 0.2f) set_door(f, r, {r.i + 1, r.j});
      if (r.j + 1 < L.nz && !special({r.i, r.j + 1}) && rng.next_float() < 0.2f) set_door(f, r, {r.i, r.j + 1});
    }
    if (L.floors > f + 1) set_door(f, L.rise(f), {L.rise(f).i - 1, L.rise(f).j});
    if (f >= 1) set_door(f, L.rise(f - 1), {L.rise(f - 1).i + 1, L.rise(f - 1).j});
  }
  return L;
}

struct Materials {
  uint32_t floor, wall, trim, crate, column, decal, ramp;
};

uint32_t gray(Scene& s, const std::string& name, vec3 color) {
  Material m;
  m.name = name;
  m.diffuse = color;
  return add_material(s, m);
}

// One wall segment on a grid line of storey f: along x (axis 0, at z = line) or along z
// (axis 1, at x = line) from a to b; with a door in the middle when `door`.
void wall_segment(LevelBuilder& B, const LevelOptions& o, const Materials& M, int f, int axis, float line,
                  float a, float b, bool door) {
  const float y0 = float(f) * kStorey, y1 = y0 + kStorey - kSlab;
  auto make = [&](float along0, float along1, float ya, float yb, float thick) {
    const float t0 = B.seam(line - 0.5f * thick), t1 = B.seam(line + 0.5f * thick);
    return axis == 0 ? B.box({along0, ya, t0}, {along1, yb, t1}) : B.box({t0, ya, along0}, {t1, yb, along1});
  };
  const uint32_t drop_bottom = B.chance(0.3f) ? kNegY : 0;
  const float lo = B.seam(a - 0.5f * kWall), hi = B.seam(b + 0.5f * kWall);
  if (!door) {
    B.emit(make(lo, hi, B.seam(y0), B.seam(y1), kWall), M.wall, "wall", drop_bottom);
    return;
  }
  const float m = 0.5f * (a + b), d0 = m - 0.5f * kDoorW, d1 = m + 0.5f * kDoorW;
  B.emit(make(lo, B.seam(d0), B.seam(y0), B.seam(y1), kWall), M.wall, "door_post", drop_bottom);
  B.emit(make(B.seam(d1), hi, B.seam(y0), B.seam(y1), kWall), M.wall, "door_post", drop_bottom);
  // Half the lintels overlap their posts (coplanar faces), half abut them (T-junctions).
  const float over = B.chance(0.5f) ? 0.25f : 0.0f;
  B.emit(make(B.seam(d0 - over), B.seam(d1 + over), B.seam(y0 + kDoorH), B.seam(y1), kWall), M.wall, "lintel");
  if (o.detail >= 1) {
    const float trim = kWall + 0.04f;
    B.emit(make(d0, d0 + 0.05f, y0, y0 + kDoorH, trim), M.trim, "jamb", kNegY);
    B.emit(make(d1 - 0.05f, d1, y0, y0 + kDoorH, trim), M.trim, "jamb", kNegY);
    B.emit(make(d0, d1, y0 + kDoorH - 0.05f, y0 + kDoorH, trim), M.trim, "head");
  }
}

// Baseboards (2 cm × 12 cm) along the inner side of one wall of a room, split at a door.
void baseboards(LevelBuilder& B, const Materials& M, int f, int axis, float face, float side, float a, float b,
                bool door) {
  const float y0 = float(f) * kStorey;
  const float embed = B.chance(0.5f) ? 0.005f : 0.0f;  // sunk into the wall, or flush against it
  const float t0 = face - side * embed, t1 = face + side * 0.02f;
  auto piece = [&](float p0, float p1) {
    const float lo = std::min(t0, t1), hi = std::max(t0, t1);
    Brush br = axis == 0 ? B.box({p0, B.seam(y0), B.seam(lo)}, {p1, y0 + 0.12f, B.seam(hi)})
                         : B.box({B.seam(lo), B.seam(y0), p0}, {B.seam(hi), y0 + 0.12f, p1});
    B.emit(br, M.trim, "baseboard", kNegY);
  };
  if (!door) {
    piece(a, b);
    return;
  }
  const float m = 0.5f * (a + b);
  piece(a, m - 0.5f * kDoorW);
  piece(m + 0.5f * kDoorW, b);
}

// One quadrant of a regular room: the area off the free cross between its doors.
void quadrant(LevelBuilder& B, const Materials& M, int f, Room r, int sx, int sz) {
  const vec3 c = center_of(r, f);
  const float y0 = c.y, ceiling = y0 + kStorey - kSlab;
  const float inner_x = 0.5f * kRoomX - 0.5f * kWall, inner_z = 0.5f * kRoomZ - 0.5f * kWall;
  const float qx0 = kCross, qx1 = inner_x - 0.25f, qz0 = kCross, qz1 = inner_z - 0.25f;
  const vec3 q{c.x + float(sx) * 0.5f * (qx0 + qx1), y0, c.z + float(sz) * 0.5f * (qz0 + qz1)};
  const float hz = 0.5f * (qz1 - qz0);
  const float fx = float(sx), fz = float(sz);
  switch (B.pick(6)) {
    case 0: {  // octagonal column sunk into both slabs, on a square plinth
      const float rad = B.uniform(0.3f, 0.45f);
      B.emit(B.prism(q, rad, y0 - 0.05f, ceiling + 0.05f, 8, B.uniform(0.0f, 0.8f)), M.column, "column");
      const float p = rad + 0.1f;
      B.emit(B.box({q.x - p, B.seam(y0), q.z - p}, {q.x + p, y0 + 0.2f, q.z + p}), M.column, "plinth",
             B.chance(0.5f) ? kNegY : 0);
      break;
    }
    case 1: {  // square column at a random yaw, floor to ceiling, with a capital
      const float yaw = B.uniform(0.0f, 1.5f);
      B.emit(B.box({q.x - 0.25f, B.seam(y0), q.z - 0.25f}, {q.x + 0.25f, B.seam(ceiling), q.z + 0.25f}, yaw),
             M.column, "column");
      B.emit(B.box({q.x - 0.35f, ceiling - 0.15f, q.z - 0.35f}, {q.x + 0.35f, ceiling, q.z + 0.35f}, yaw), M.column,
             "capital", kPosY);
      break;
    }
    case 2: {  // crates: one on the floor, one stacked on it, one sunk into it
      const float s1 = B.uniform(0.6f, 1.0f), s2 = B.uniform(0.4f, s1);
      const float yaw1 = B.uniform(-0.25f, 0.25f);
      B.emit(B.box({q.x - 0.5f * s1, y0, q.z - 0.5f * s1}, {q.x + 0.5f * s1, y0 + s1, q.z + 0.5f * s1}, yaw1), M.crate,
             "crate", kNegY);
      B.emit(B.box({q.x - 0.5f * s2, y0 + s1, q.z - 0.5f * s2}, {q.x + 0.5f * s2, y0 + s1 + s2, q.z + 0.5f * s2},
                   B.uniform(-0.6f, 0.6f)),
             M.crate, "crate");
      const float ox = q.x + fx * 0.4f, s3 = 0.5f;
      B.emit(B.box({ox - 0.5f * s3, y0, q.z - 0.5f * s3}, {ox + 0.5f * s3, y0 + s3, q.z + 0.5f * s3}), M.crate, "crate");
      break;
    }
    case 3: {  // platform against the outer wall, a wedge up to it, a 1.5 cm edge trim (a sliver)
      const float outer = c.x + fx * qx1;
      const float p0 = std::min(outer, outer - fx * 1.0f), p1 = std::max(outer, outer - fx * 1.0f);
      B.emit(B.box({p0, y0, q.z - hz}, {p1, y0 + 0.6f, q.z + hz}), M.crate, "platform", kNegY);
      const float w0 = std::min(outer - fx * 1.0f, outer - fx * 2.2f), w1 = std::max(outer - fx * 1.0f, outer - fx * 2.2f);
      B.emit(B.wedge({w0, y0, q.z - 0.6f}, {w1, y0 + 0.6f, q.z + 0.6f}, sx > 0 ? 0.0f : kPi), M.ramp, "wedge",
             1);  // bit 0: a wedge's bottom face
      const float e = outer - fx * 1.0f;
      B.emit(B.box({std::min(e, e + fx * 0.03f), y0 + 0.6f, q.z - hz}, {std::max(e, e + fx * 0.03f), y0 + 0.615f, q.z + hz}),
             M.trim, "edge_trim", kNegY);
      break;
    }
    case 4: {  // angled wall across the room corner, ends in the room walls, no top face
      const vec3 corner{c.x + fx * inner_x, y0, c.z + fz * inner_z};
      const vec3 mid = corner - vec3(fx * 0.9f, 0.0f, fz * 0.9f);
      const float yaw = std::atan2(fz, fx);
      B.emit(B.box({mid.x - 1.45f, y0, mid.z - 0.075f}, {mid.x + 1.45f, y0 + 2.8f, mid.z + 0.075f}, yaw), M.wall,
             "angled_wall", kPosY | kNegY);
      break;
    }
    default:
      break;
  }
}

}  // namespace

Scene make_level(const LevelOptions& o) {
  require_in_range(o.rooms_x, 3, 64, "level: rooms_x");
  require_in_range(o.rooms_z, 3, 64, "level: rooms_z");
  require_in_range(o.floors, 2, 16, "level: floors");
  require_in_range(o.detail, 0, 1, "level: detail");
  require_in_range(o.seam_jitter, 0.0f, 0.01f, "level: seam_jitter", "m");
  Scene s;
  s.name = o.name;
  Pcg32 plan_rng(o.seed, 0x91a7);
  const Layout L = plan(o, plan_rng);
  LevelBuilder B(s, o);
  Materials M;
  M.floor = gray(s, "floor", {0.45f, 0.42f, 0.38f});
  M.wall = gray(s, "wall", {0.75f, 0.72f, 0.65f});
  M.trim = gray(s, "trim", {0.35f, 0.25f, 0.18f});
  M.crate = gray(s, "crate", {0.6f, 0.45f, 0.25f});
  M.column = gray(s, "column", {0.6f, 0.6f, 0.62f});
  M.decal = gray(s, "decal", {0.8f, 0.2f, 0.15f});
  M.ramp = gray(s, "ramp", {0.5f, 0.5f, 0.45f});

  // Slabs: one per room and level (level = storey floor, the last one the roof), grown by
  // half a wall on each side so neighbors overlap under the walls; over a rise room the slab
  // above is two strips beside the hole.
  for (int level = 0; level <= L.floors; ++level) {
    const float top = float(level) * kStorey, bottom = top - kSlab;
    for (int k = 0; k < L.nx * L.nz; ++k) {
      const Room r = L.room(k);
      const float xa = B.seam(x0_of(r) - 0.5f * kWall), xb = B.seam(x0_of(r) + kRoomX + 0.5f * kWall);
      const float za = B.seam(z0_of(r) - 0.5f * kWall), zb = B.seam(z0_of(r) + kRoomZ + 0.5f * kWall);
      // The ground's bottom and the roof's top face the void outside: dropped at random, as
      // editors drop faces no one can see.
      const uint32_t drop = level == 0 && B.chance(0.5f) ? uint32_t(kNegY) : level == L.floors && B.chance(0.5f) ? uint32_t(kPosY) : 0u;
      if (level >= 1 && L.is_rise(level - 1, r)) {
        const float zc = z0_of(r) + 0.5f * kRoomZ;
        B.emit(B.box({xa, bottom, za}, {xb, top, B.seam(zc - kBand)}), M.floor, "slab_strip");
        B.emit(B.box({xa, bottom, B.seam(zc + kBand)}, {xb, top, zb}), M.floor, "slab_strip");
      } else {
        B.emit(B.box({xa, B.seam(bottom), za}, {xb, top, zb}), M.floor, level == L.floors ? "roof" : "slab", drop);
      }
    }
  }

  for (int f = 0; f < L.floors; ++f) {
    const float y0 = float(f) * kStorey;
    // Walls on the grid lines: lines x = i·kRoomX (along z) and z = j·kRoomZ (along x).
    for (int i = 0; i <= L.nx; ++i)
      for (int j = 0; j < L.nz; ++j) {
        const bool door = i > 0 && i < L.nx && L.has_door(f, {i - 1, j}, {i, j});
        wall_segment(B, o, M, f, 1, float(i) * kRoomX, float(j) * kRoomZ, float(j + 1) * kRoomZ, door);
      }
    for (int j = 0; j <= L.nz; ++j)
      for (int i = 0; i < L.nx; ++i) {
        const bool door = j > 0 && j < L.nz && L.has_door(f, {i, j - 1}, {i, j});
        wall_segment(B, o, M, f, 0, float(j) * kRoomZ, float(i) * kRoomX, float(i + 1) * kRoomX, door);
      }
    for (int k = 0; k < L.nx * L.nz; ++k) {
      const Room r = L.room(k);
      const vec3 c = center_of(r, f);
      const float xi0 = x0_of(r) + 0.5f * kWall, xi1 = x0_of(r) + kRoomX - 0.5f * kWall;
      const float zi0 = z0_of(r) + 0.5f * kWall, zi1 = z0_of(r) + kRoomZ - 0.5f * kWall;
      const float ceiling = y0 + kStorey - kSlab;
      if (L.is_rise(f, r)) {
        if (f % 2 == 0) {
          B.emit(B.wedge({xi0, y0, B.seam(c.z - kBand)}, {xi1, y0 + kStorey, B.seam(c.z + kBand)}), M.ramp, "ramp",
                 B.chance(0.5f) ? 1u : 0u);
        } else {
          const float run = (xi1 - xi0) / float(kSteps), rise = kStorey / float(kSteps);
          for (int st = 0; st < kSteps; ++st) {
            const float a = B.seam(xi0 + float(st) * run);
            const float b = B.chance(0.5f) ? xi1 : B.seam(xi0 + float(st + 1) * run);  // solid or single step
            B.emit(B.box({a, y0, c.z - kBand}, {b, B.seam(y0 + float(st + 1) * rise), c.z + kBand}), M.ramp, "step",
                   kNegY);
          }
        }
      }
      if (o.detail >= 1 && L.is_landing(f, r)) {
        // Railings along both edges of the slab hole: 4 cm posts every metre and a top rail.
        for (int side = -1; side <= 1; side += 2) {
          const float z = c.z + float(side) * (kBand + 0.05f);
          for (float x = xi0 + 0.3f; x < xi1 - 1.0f; x += 1.0f)
            B.emit(B.box({x - 0.02f, y0, z - 0.02f}, {x + 0.02f, y0 + 1.0f, z + 0.02f}), M.trim, "rail_post", kNegY);
          B.emit(B.box({xi0 + 0.28f, y0 + 1.0f, z - 0.03f}, {xi1 - 1.0f, y0 + 1.04f, z + 0.03f}), M.trim, "rail");
        }
      }
      if (!L.is_rise(f, r) && !L.is_landing(f, r))
        for (int sx = -1; sx <= 1; sx += 2)
          for (int sz = -1; sz <= 1; sz += 2) quadrant(B, M, f, r, sx, sz);
      if (o.detail >= 1) {
        if (!L.is_landing(f, r) && !L.is_rise(f, r))
          B.emit(B.box({c.x - 0.25f, ceiling - 0.06f, c.z - 0.25f}, {c.x + 0.25f, ceiling, c.z + 0.25f}), M.trim, "light",
                 kPosY);
        const bool dw = r.i > 0 && L.has_door(f, {r.i - 1, r.j}, r), de = r.i + 1 < L.nx && L.has_door(f, r, {r.i + 1, r.j});
        const bool ds = r.j > 0 && L.has_door(f, {r.i, r.j - 1}, r), dn = r.j + 1 < L.nz && L.has_door(f, r, {r.i, r.j + 1});
        if (!L.is_rise(f, r) && !L.is_landing(f, r)) {
          baseboards(B, M, f, 1, xi0, 1.0f, zi0, zi1, dw);
          baseboards(B, M, f, 1, xi1, -1.0f, zi0, zi1, de);
          baseboards(B, M, f, 0, zi0, 1.0f, xi0, xi1, ds);
          baseboards(B, M, f, 0, zi1, -1.0f, xi0, xi1, dn);
        }
        // A decal on the −z wall, exactly on it (coplanar) or 1 mm in front.
        const float off = B.chance(0.5f) ? 0.0f : 0.001f;
        B.quad({xi0 + 0.6f, y0 + 1.2f, zi0 + off}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.7f, 0.0f}, M.decal, "decal");
      }
    }
  }

  // Lights: one point light under the ceiling of each storey's first room.
  for (int f = 0; f < L.floors; ++f) {
    PointLight l;
    l.position = center_of({0, 0}, f) + vec3(0.0f, 2.8f, 0.0f);
    l.intensity = vec3(40.0f);
    s.point_lights.push_back(l);
  }
  s.ambient = vec3(0.3f);

  // The walk: a depth-first tour (to depth 2, back to the start) of storey 0 from room
  // (0, 0), up the ramp of the rise room (1, 0), then a tour of storey 1 from room (2, 0).
  std::vector<vec3> pts;
  const vec3 eye(0.0f, kEye, 0.0f);
  auto door_point = [&](Room a, Room b, int f) {
    return 0.5f * (center_of(a, f) + center_of(b, f)) + eye;
  };
  auto tour = [&](auto&& self, int f, Room u, int depth) -> void {
    pts.push_back(center_of(u, f) + eye);
    if (depth >= 2) return;
    for (int v : L.children[size_t(f)][size_t(L.id(u))]) {
      const Room rv = L.room(v);
      pts.push_back(door_point(u, rv, f));
      self(self, f, rv, depth + 1);
      pts.push_back(door_point(u, rv, f));
      pts.push_back(center_of(u, f) + eye);
    }
  };
  tour(tour, 0, {0, 0}, 0);
  const Room ramp_room = L.rise(0);
  pts.push_back(door_point({0, 0}, ramp_room, 0));
  pts.push_back(center_of(ramp_room, 0) + vec3(0.0f, 0.5f * kStorey, 0.0f) + eye);
  pts.push_back(door_point(ramp_room, {2, 0}, 1));
  tour(tour, 1, {2, 0}, 0);
  CameraPath walk;
  walk.name = "walk";
  walk.frames = 150;
  for (size_t i = 0; i < pts.size(); ++i) {
    CameraKey k;
    k.time = float(i);
    k.position = pts[i];
    k.target = i + 1 < pts.size() ? pts[i + 1] : pts[i] + (pts[i] - pts[i - 1]);
    k.vfov_deg = 75.0f;
    walk.keys.push_back(k);
  }
  s.camera_paths.push_back(walk);
  s.cameras.push_back({"walk_start", camera_at_time(walk, frame_time(walk, 0), 512, 512, 0.01f, 1000.0f)});
  return s;
}

namespace {

struct NamedLevel {
  const char* name;
  int rooms_x, rooms_z, floors, detail;
};

constexpr NamedLevel kLevels[] = {
    {"level-small", 3, 3, 2, 0},
    {"level-medium", 4, 3, 2, 1},
    {"level-large", 6, 4, 3, 1},
    {"level-huge", 8, 8, 3, 1},
};

}  // namespace

bool is_level_scene(const std::string& name) {
  return std::any_of(std::begin(kLevels), std::end(kLevels), [&](const NamedLevel& l) { return name == l.name; });
}

LevelOptions level_options(const std::string& name) {
  for (const NamedLevel& l : kLevels) {
    if (name != l.name) continue;
    LevelOptions o;
    o.name = l.name;
    o.rooms_x = l.rooms_x;
    o.rooms_z = l.rooms_z;
    o.floors = l.floors;
    o.detail = l.detail;
    o.seed = 1;
    return o;
  }
  fail_input("unknown level '" + name + "' (known: level-small, level-medium, level-large, level-huge)");
}

}  // namespace proxima
