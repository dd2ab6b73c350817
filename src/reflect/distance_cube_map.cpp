// Distance cube map — Wang, Tang, Sun, Ma, "Environment mapping with position
// rectification", J. Image and Graphics 17(3), 2012, §2.1 (papers/000_…, line 241).
//
// Paper symbol ↔ variable:
//   projection center (the origin of §2.2)   map.camera.center (c)
//   L_env(l).rgb, L_env(l).a = d              CubeSample::color, CubeSample::distance
//   d_inf                                     kDistanceInf (+inf: every distance is below it)
// The paper renders the map on the GPU with alpha initialised to d_inf; here each face is
// a raster/ G-buffer (triangle, barycentrics, object) and each covered texel is shaded
// with the reference's local model, Embree shadows included (trace/direct_light.h).
#include "proxima/reflect/distance_cube_map.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/raster/depth_peeling.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/trace/direct_light.h"

namespace proxima {
namespace {

constexpr int kTileSize = 32;

// The objects to draw: options.objects, or all but options.exclude.
std::vector<uint32_t> draw_list(const Scene& scene, const DistanceCubeMapOptions& options) {
  if (!options.objects.empty()) return {options.objects.begin(), options.objects.end()};
  std::vector<uint32_t> out;
  for (uint32_t o = 0; o < uint32_t(scene.objects.size()); ++o)
    if (std::find(options.exclude.begin(), options.exclude.end(), o) == options.exclude.end())
      out.push_back(o);
  return out;
}

struct TapRef {
  int face, x, y;
};

// Texel (x, y) of `face`, possibly one beyond an edge: beyond, the texel of the face that
// the extrapolated texel-center direction falls in (nearest, clamped into that face).
TapRef resolve_tap(const DistanceCubeMap& map, int face, int x, int y) {
  const int res = map.camera.resolution;
  if (x >= 0 && x < res && y >= 0 && y < res) return {face, x, y};
  vec3 dir = unproject(map.face_cams[size_t(face)], vec2(float(x) + 0.5f, float(y) + 0.5f), 1.0f) -
             map.camera.center;
  CubeTexel t = cube_lookup(map.camera, dir);
  return {t.face, std::clamp(int(std::floor(t.pixel.x)), 0, res - 1),
          std::clamp(int(std::floor(t.pixel.y)), 0, res - 1)};
}

}  // namespace

namespace {

void check_resolution(int resolution) {
  static_assert(kMaxImageSide == 16384);
  if (resolution < 1 || resolution > kMaxImageSide) fail_input("distance cube map: resolution must be in 1..16384");
}

// An empty map around `center`: camera, face cameras and their bases.
DistanceCubeMap empty_map(const Scene& scene, vec3 center, int resolution) {
  const float diagonal = std::max(scene_bounds(scene).diagonal(), 1e-3f);
  DistanceCubeMap map;
  map.camera = CubeCamera{center, resolution, 1e-4f * diagonal, 4.0f * diagonal};
  map.face_cams = face_cameras(map.camera);
  for (size_t f = 0; f < 6; ++f)
    map.face_basis[f] = {camera_right(map.face_cams[f]), camera_up(map.face_cams[f]),
                         camera_forward(map.face_cams[f])};
  return map;
}

// Stores face f of `map` from its G-buffer `g`: every covered texel for which keep(x, y)
// holds is shaded (stream derive_seed(seed, stream_face, texel)); covered texels not kept
// count as hidden. A face with nothing stored stays unallocated.
template <typename Keep>
void store_face(const Scene& scene, const DirectLight& light, const DistanceCubeMapOptions& options,
                DistanceCubeMap& map, int f, uint64_t stream_face, const RasterImages& g, Keep&& keep) {
  const int res = map.camera.resolution;
  const vec3 center = map.camera.center;
  size_t face_covered = 0, face_hidden = 0;
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      if (g.triangle.at(x, y) == kNoTriangle) continue;
      if (keep(x, y))
        ++face_covered;
      else
        ++face_hidden;
    }
  map.hidden_texels += face_hidden;
  if (face_covered == 0) return;  // leave the face empty: no memory for layers that miss it
  map.shaded_texels += face_covered;
  ImageF& face = map.faces[size_t(f)];
  face = ImageF(res, res, 4, 0.0f);
  ImageF& distance = map.distances[size_t(f)];
  distance = ImageF(res, res, 1, kDistanceInf);
  ImageU32& objects = map.objects[size_t(f)];
  objects = ImageU32(res, res, 1, kNoObject);
  parallel_for_tiles(res, res, kTileSize, [&](const Tile& tile) {
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const uint32_t t = g.triangle.at(x, y);
        if (t == kNoTriangle || !keep(x, y)) {
          face.at(x, y, 3) = kDistanceInf;
          continue;
        }
        vec3 p = triangle_point(scene, t, g.barycentric.at(x, y, 0), g.barycentric.at(x, y, 1));
        SurfacePoint sp =
            surface_point_seen(scene, t, g.barycentric.at(x, y, 0), g.barycentric.at(x, y, 1), p - center);
        Pcg32 rng(derive_seed(options.seed, stream_face, uint64_t(y) * uint64_t(res) + uint64_t(x)));
        // Texels are one bounce deep: their own reflections are beyond the bounce limit.
        vec3 color = options.shade ? options.shade(t, sp.u, sp.v, center - p)
                                   : combine_shading(light.local_terms(sp, rng));
        for (int c = 0; c < 3; ++c) face.at(x, y, c) = color[c];
        face.at(x, y, 3) = distance.at(x, y) = glm::length(p - center);
        objects.at(x, y) = g.object.at(x, y);
      }
  });
  for (float d : distance.data()) map.min_distance = std::min(map.min_distance, d);
}

RasterOptions gbuffer_options(const std::vector<uint32_t>& objects, const std::vector<Bounds3>& bounds) {
  RasterOptions ro;
  ro.outputs = kRasterDepthId | kRasterBarycentric | kRasterObject;
  ro.objects = objects;
  ro.object_bounds = bounds;
  return ro;
}

}  // namespace

DistanceCubeMap render_distance_cube_map(const Scene& scene, const RayScene& rays, vec3 center,
                                         const DistanceCubeMapOptions& options) {
  check_resolution(options.resolution);
  DistanceCubeMap map = empty_map(scene, center, options.resolution);
  const std::vector<uint32_t> objects = draw_list(scene, options);
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  const RasterOptions ro = gbuffer_options(objects, bounds);
  const DirectLight light(scene, rays, options.area_light_samples);
  RasterImages g;
  for (int f = 0; f < 6 && !objects.empty(); ++f) {
    rasterize(scene, map.face_cams[size_t(f)], ro, g, AcceptAllFragments{});
    store_face(scene, light, options, map, f, uint64_t(f), g, [](int, int) { return true; });
  }
  const double res = double(options.resolution);
  map.covered_fraction = double(map.shaded_texels) / (6.0 * res * res);
  return map;
}

namespace {

constexpr int kReachTile = 16;  // texels per side of the reachability tiles

// Euclidean distance to c of every covered texel of a G-buffer (+inf where empty).
ImageF texel_distances(const Scene& scene, const RasterImages& g, vec3 center) {
  ImageF d(g.triangle.width(), g.triangle.height(), 1, kDistanceInf);
  parallel_for(size_t(d.height()), 16, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < d.width(); ++x) {
        const uint32_t t = g.triangle.at(x, y);
        if (t != kNoTriangle)
          d.at(x, y) = glm::length(triangle_point(scene, t, g.barycentric.at(x, y, 0), g.barycentric.at(x, y, 1)) -
                                   center);
      }
  });
  return d;
}

// Per reachability tile (face-major, row-major): whether a ray from within r of c can get
// behind the layer whose per-face distances are `dist` somewhere in the tile — some
// depth discontinuity of that layer lies within asin(r/ρ) (ρ: the discontinuity's near
// side) plus the tiles' angular radii; and the tile was reachable for the layer before.
std::vector<uint8_t> reachable_tiles(const DistanceCubeMap& geometry, const std::array<ImageF, 6>& dist,
                                     const std::vector<uint8_t>& reachable_before, float r, float edge_jump) {
  const int res = geometry.camera.resolution;
  const int nt = (res + kReachTile - 1) / kReachTile;
  const size_t n_tiles = size_t(6) * size_t(nt) * size_t(nt);
  const vec3 c = geometry.camera.center;
  // Tile centre directions and angular radii (to the farthest corner).
  std::vector<vec3> centre(n_tiles);
  std::vector<float> radius(n_tiles);
  for (int f = 0; f < 6; ++f)
    for (int ty = 0; ty < nt; ++ty)
      for (int tx = 0; tx < nt; ++tx) {
        const size_t i = (size_t(f) * size_t(nt) + size_t(ty)) * size_t(nt) + size_t(tx);
        const float x0 = float(tx * kReachTile), y0 = float(ty * kReachTile);
        const float x1 = float(std::min(res, (tx + 1) * kReachTile)), y1 = float(std::min(res, (ty + 1) * kReachTile));
        const Camera& cam = geometry.face_cams[size_t(f)];
        auto dir = [&](float px, float py) { return glm::normalize(unproject(cam, vec2(px, py), 1.0f) - c); };
        centre[i] = dir(0.5f * (x0 + x1), 0.5f * (y0 + y1));
        float cos_min = 1.0f;
        for (vec2 corner : {vec2(x0, y0), vec2(x1, y0), vec2(x0, y1), vec2(x1, y1)})
          cos_min = std::min(cos_min, glm::dot(centre[i], dir(corner.x, corner.y)));
        radius[i] = std::acos(std::clamp(cos_min, -1.0f, 1.0f));
      }
  // Per tile, the largest reach angle asin(r/ρ) of a discontinuity between one of its
  // texels and the right or lower neighbour (across a face edge: the neighbouring face's texel).
  std::vector<float> reach(n_tiles, -1.0f);
  parallel_for(size_t(6) * size_t(nt), 1, [&](size_t b, size_t e) {
    for (size_t row = b; row < e; ++row) {
      const int f = int(row / size_t(nt)), ty = int(row % size_t(nt));
      for (int y = ty * kReachTile; y < std::min(res, (ty + 1) * kReachTile); ++y)
        for (int x = 0; x < res; ++x) {
          const float a = dist[size_t(f)].at(x, y);
          for (int k = 0; k < 2; ++k) {
            const int nx = x + (k == 0), ny = y + (k == 1);
            const TapRef n = resolve_tap(geometry, f, nx, ny);
            const float bd = dist[size_t(n.face)].at(n.x, n.y);
            const float near = std::min(a, bd), far = std::max(a, bd);
            if (near == kDistanceInf) continue;  // both empty
            if (far != kDistanceInf && far - near <= edge_jump * near) continue;
            const float angle = near > r ? std::asin(r / near) : kPi;
            float& t = reach[(size_t(f) * size_t(nt) + size_t(ty)) * size_t(nt) + size_t(x / kReachTile)];
            t = std::max(t, angle);
          }
        }
    }
  });
  std::vector<size_t> edges;
  for (size_t i = 0; i < n_tiles; ++i)
    if (reach[i] >= 0.0f) edges.push_back(i);
  // Margin: the discontinuity lies up to one texel outside its tile (≤ 2/res rad).
  const float margin = 3.0f / float(res);
  std::vector<uint8_t> out(n_tiles, 0);
  parallel_for(n_tiles, 64, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (!reachable_before.empty() && !reachable_before[i]) continue;
      for (size_t j : edges) {
        const float angle = reach[j] + radius[j] + radius[i] + margin;
        if (angle >= kPi || glm::dot(centre[i], centre[j]) >= std::cos(angle)) {
          out[i] = 1;
          break;
        }
      }
    }
  });
  return out;
}

// Triangles of `objects` that a ray from the sphere (c, r) can meet from the front: the
// sphere is not wholly behind the triangle's plane (degenerate triangles are kept).
std::vector<uint32_t> front_triangles(const Scene& scene, const std::vector<uint32_t>& objects, vec3 c, float r) {
  std::vector<uint32_t> out;
  for (uint32_t o : objects) {
    const Object& obj = scene.objects[o];
    for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
      const vec3 n = triangle_normal(scene, t);
      const vec3 p0 = scene.positions[scene.triangles[t].x];
      const float len = glm::length(n);
      if (!(len > 0.0f) || glm::dot(n, c - p0) >= -r * len * 1.0001f - 1e-6f) out.push_back(t);
    }
  }
  return out;
}

}  // namespace

std::vector<DistanceCubeMap> render_distance_cube_layers(const Scene& scene, const RayScene& rays, vec3 center,
                                                         const DistanceCubeMapOptions& options,
                                                         const DistanceCubeLayerOptions& lo) {
  check_resolution(options.resolution);
  if (lo.layers < 1 || lo.layers > kMaxDistanceCubeLayers)
    fail_input("distance cube layers: the layer count must be in 1..16");
  const int res = options.resolution;
  const std::vector<uint32_t> objects = draw_list(scene, options);
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  const RasterOptions ro0 = gbuffer_options(objects, bounds);
  const float r = std::max(lo.viewer_radius, 0.0f);
  const std::vector<uint32_t> peel_triangles =
      lo.cull_back_faces ? front_triangles(scene, objects, center, r) : std::vector<uint32_t>{};
  RasterOptions ro1 = ro0;
  if (lo.cull_back_faces) {
    ro1.objects = {};
    ro1.triangles = peel_triangles;
  }
  const DirectLight light(scene, rays, options.area_light_samples);

  std::vector<DistanceCubeMap> layers;
  std::array<RasterImages, 6> previous, current;
  std::array<ImageF, 6> previous_distance;
  std::vector<uint8_t> reachable;  // per tile, for the current layer (empty: all)
  const int nt = (res + kReachTile - 1) / kReachTile;
  for (int k = 0; k < lo.layers && !objects.empty(); ++k) {
    if (k >= 1 && lo.cull_back_faces && peel_triangles.empty()) break;
    DistanceCubeMap map = empty_map(scene, center, res);
    uint64_t fragments = 0;
    for (int f = 0; f < 6; ++f) {
      const Camera& cam = map.face_cams[size_t(f)];
      if (k == 0)
        fragments += rasterize(scene, cam, ro0, current[size_t(f)], AcceptAllFragments{}).fragments_written;
      else
        fragments += rasterize(scene, cam, ro1, current[size_t(f)],
                               BehindLayerTest{previous[size_t(f)].depth, previous[size_t(f)].triangle,
                                               lo.min_separation})
                         .fragments_written;
    }
    if (fragments == 0) break;  // nothing behind the previous layer
    if (k >= 1 && lo.reachable_only)
      reachable = reachable_tiles(map, previous_distance, reachable, r, lo.edge_jump);
    for (int f = 0; f < 6; ++f) {
      const uint64_t stream = k == 0 ? uint64_t(f) : uint64_t(6 * k + f);
      if (reachable.empty()) {
        store_face(scene, light, options, map, f, stream, current[size_t(f)], [](int, int) { return true; });
      } else {
        const uint8_t* tiles = reachable.data() + size_t(f) * size_t(nt) * size_t(nt);
        store_face(scene, light, options, map, f, stream, current[size_t(f)], [tiles, nt](int x, int y) {
          return tiles[size_t(y / kReachTile) * size_t(nt) + size_t(x / kReachTile)] != 0;
        });
      }
      if (k + 1 < lo.layers && lo.reachable_only)
        previous_distance[size_t(f)] = texel_distances(scene, current[size_t(f)], center);
    }
    map.covered_fraction = double(map.shaded_texels) / (6.0 * double(res) * double(res));
    std::swap(previous, current);
    if (k >= 1 && map.shaded_texels == 0) break;  // nothing reachable here, so nothing deeper either
    layers.push_back(std::move(map));
  }
  return layers;
}

namespace {

// The face `dir` falls in and its four bilinear taps (texel centers at +0.5): *x0, *y0 the
// upper-left tap, weights in tap order (x0, y0), (x0 + 1, y0), (x0, y0 + 1), (x0 + 1, y0 + 1).
// Returns the face, or −1 for a zero or NaN dir.
int bilinear_taps(const DistanceCubeMap& map, vec3 dir, int* x0, int* y0, float weights[4]) {
  // The face and continuous pixel of cube_lookup(), with the cached face frames.
  const vec3 a = glm::abs(dir);
  int face;
  if (a.x >= a.y && a.x >= a.z)
    face = dir.x >= 0.0f ? 0 : 1;
  else if (a.y >= a.z)
    face = dir.y >= 0.0f ? 2 : 3;
  else
    face = dir.z >= 0.0f ? 4 : 5;
  const auto& basis = map.face_basis[size_t(face)];
  const float half = 0.5f * float(map.camera.resolution);
  const float depth = glm::dot(dir, basis[2]);  // ≥ |dir|/√3 on the chosen face
  if (!(depth > 0.0f)) return -1;               // dir = 0 or NaN: nothing to look up
  const float scale = half / depth;
  const float fx = half + glm::dot(dir, basis[0]) * scale - 0.5f;
  const float fy = half - glm::dot(dir, basis[1]) * scale - 0.5f;
  *x0 = int(std::floor(fx));
  *y0 = int(std::floor(fy));
  const float ax = fx - float(*x0), ay = fy - float(*y0);
  weights[0] = (1 - ax) * (1 - ay);
  weights[1] = ax * (1 - ay);
  weights[2] = (1 - ax) * ay;
  weights[3] = ax * ay;
  return face;
}

// Bilinear filter of `dir` over the non-empty texels; with kColor false only the distance.
// Returns the covered weight (the sum of the non-empty taps' weights).
template <bool kColor>
float filter(const DistanceCubeMap& map, vec3 dir, vec3* color, float* distance, uint32_t* object,
             float* tap_min = nullptr, float* tap_max = nullptr, bool* one_object = nullptr) {
  int x0 = 0, y0 = 0;
  float weights[4];
  const int face = bilinear_taps(map, dir, &x0, &y0, weights);
  if (face < 0) return 0.0f;
  const int res = map.camera.resolution;
  const bool inside = x0 >= 0 && y0 >= 0 && x0 + 1 < res && y0 + 1 < res;
  if constexpr (!kColor) {
    // Fast path of the bisection's steps: all four taps on one face and non-empty.
    const ImageF& img = map.distances[size_t(face)];
    if (inside && !img.empty()) {
      const float* r0 = &img.at(x0, y0);
      const float* r1 = r0 + res;
      if (std::max(std::max(r0[0], r0[1]), std::max(r1[0], r1[1])) < kDistanceInf) {
        *distance = weights[0] * r0[0] + weights[1] * r0[1] + weights[2] * r1[0] + weights[3] * r1[1];
        return 1.0f;
      }
    }
  }

  float covered = 0.0f, best = -1.0f, d_sum = 0.0f;
  uint32_t first_object = kNoObject;
  vec3 c_sum(0.0f);
  for (int k = 0; k < 4; ++k) {
    if (weights[k] <= 0.0f) continue;
    TapRef tap = inside ? TapRef{face, x0 + (k & 1), y0 + (k >> 1)}
                        : resolve_tap(map, face, x0 + (k & 1), y0 + (k >> 1));
    const ImageF& img = kColor ? map.faces[size_t(tap.face)] : map.distances[size_t(tap.face)];
    if (img.empty()) continue;
    const float* texel = &img.at(tap.x, tap.y, 0);
    const float d = kColor ? texel[3] : texel[0];
    if (d == kDistanceInf) continue;
    d_sum += weights[k] * d;
    if constexpr (!kColor) covered += weights[k];
    if constexpr (kColor) {
      const uint32_t o = map.objects[size_t(tap.face)].at(tap.x, tap.y);
      if (covered > 0.0f && o != first_object) *one_object = false;
      first_object = o;
      *tap_min = std::min(*tap_min, d);
      *tap_max = std::max(*tap_max, d);
      c_sum += weights[k] * vec3(texel[0], texel[1], texel[2]);
      covered += weights[k];
      if (weights[k] > best) {
        best = weights[k];
        *object = map.objects[size_t(tap.face)].at(tap.x, tap.y);
      }
    }
  }
  if (covered >= 0.5f) {
    *distance = d_sum / covered;
    if constexpr (kColor) *color = c_sum / covered;
  }
  return covered;
}

// The non-empty bilinear taps of one object: summed weight, weighted distance and color,
// and the range of their distances.
struct ObjectTaps {
  uint32_t object = kNoObject;
  float weight = 0.0f, distance = 0.0f, tap_min = kDistanceInf, tap_max = 0.0f;
  vec3 color{0.0f};

  // The taps alone, weights renormalized over them.
  CubeSample sample() const {
    return {.color = color / weight, .distance = distance / weight, .object = object, .empty = false,
            .tap_min = tap_min, .tap_max = tap_max, .one_object = true};
  }
};

// The non-empty taps of `dir` grouped by object (at most four groups); returns how many.
int object_taps(const DistanceCubeMap& map, vec3 dir, ObjectTaps groups[4]) {
  int x0 = 0, y0 = 0;
  float weights[4];
  const int face = bilinear_taps(map, dir, &x0, &y0, weights);
  if (face < 0) return 0;
  int n = 0;
  for (int k = 0; k < 4; ++k) {
    if (weights[k] <= 0.0f) continue;
    const TapRef tap = resolve_tap(map, face, x0 + (k & 1), y0 + (k >> 1));
    const ImageF& img = map.faces[size_t(tap.face)];
    if (img.empty()) continue;
    const float* texel = &img.at(tap.x, tap.y, 0);
    if (texel[3] == kDistanceInf) continue;
    const uint32_t o = map.objects[size_t(tap.face)].at(tap.x, tap.y);
    int g = 0;
    while (g < n && groups[g].object != o) ++g;
    if (g == n) groups[n++] = ObjectTaps{o};
    ObjectTaps& t = groups[g];
    t.weight += weights[k];
    t.distance += weights[k] * texel[3];
    t.color += weights[k] * vec3(texel[0], texel[1], texel[2]);
    t.tap_min = std::min(t.tap_min, texel[3]);
    t.tap_max = std::max(t.tap_max, texel[3]);
  }
  return n;
}

// Distance of texel (x, y) of `face`, up to two beyond an edge (the neighbouring face's texel).
float texel_distance(const DistanceCubeMap& map, int face, int x, int y) {
  const TapRef t = resolve_tap(map, face, x, y);
  const ImageF& img = map.distances[size_t(t.face)];
  return img.empty() ? kDistanceInf : img.at(t.x, t.y);
}

// Neighbouring texels a, b with a' before a and b' after b on their row or column: the
// lines through (a', a) and (b, b') meet the midpoint of a and b within `tolerance` plus
// half their slopes' difference (a plane, or a crease anywhere between a and b), where a
// silhouette's step leaves them apart by the step.
bool pair_continuous(float a_out, float a, float b, float b_out, float tolerance) {
  if (a == kDistanceInf || b == kDistanceInf) return false;
  float sa = a_out == kDistanceInf ? kDistanceInf : a - a_out;
  float sb = b_out == kDistanceInf ? kDistanceInf : b_out - b;
  if (sa == kDistanceInf) sa = sb == kDistanceInf ? 0.0f : sb;
  if (sb == kDistanceInf) sb = sa;
  return std::abs((a + 0.5f * sa) - (b - 0.5f * sb)) <= 0.5f * std::abs(sa - sb) + tolerance;
}

}  // namespace

CubeSample sample_cube(const DistanceCubeMap& map, vec3 dir) {
  CubeSample s;
  uint32_t object = s.object;
  vec3 color(0.0f);
  float distance = kDistanceInf, tap_min = kDistanceInf, tap_max = 0.0f;
  bool one_object = true;
  if (filter<true>(map, dir, &color, &distance, &object, &tap_min, &tap_max, &one_object) < 0.5f) return s;
  s.one_object = one_object;
  s.empty = false;
  s.tap_min = tap_min;
  s.tap_max = tap_max;
  s.color = color;
  s.distance = distance;
  s.object = object;
  return s;
}

CubeSample sample_cube_surface(const DistanceCubeMap& map, vec3 dir, float rho) {
  ObjectTaps groups[4];
  const int n = object_taps(map, dir, groups);
  int best = -1;
  for (int g = 0; g < n; ++g)
    if (best < 0 || std::abs(groups[g].distance / groups[g].weight - rho) <
                        std::abs(groups[best].distance / groups[best].weight - rho))
      best = g;
  return best < 0 ? CubeSample{} : groups[best].sample();
}

CubeSample sample_cube_object(const DistanceCubeMap& map, vec3 dir, uint32_t object) {
  ObjectTaps groups[4];
  const int n = object_taps(map, dir, groups);
  for (int g = 0; g < n; ++g)
    if (groups[g].object == object && groups[g].weight >= 0.5f) return groups[g].sample();
  return {};
}

bool cube_taps_continuous(const DistanceCubeMap& map, vec3 dir, float tolerance) {
  int x0 = 0, y0 = 0;
  float weights[4];
  const int face = bilinear_taps(map, dir, &x0, &y0, weights);
  if (face < 0) return false;
  float d[4][4];  // d[j][i]: texel (x0 − 1 + i, y0 − 1 + j)
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) d[j][i] = texel_distance(map, face, x0 - 1 + i, y0 - 1 + j);
  for (int k = 0; k < 2; ++k) {
    // Row y0 + k between x0 and x0 + 1, column x0 + k between y0 and y0 + 1 (pairs of positive weight).
    if (weights[2 * k] + weights[2 * k + 1] > 0.0f && weights[2 * k] > 0.0f && weights[2 * k + 1] > 0.0f &&
        !pair_continuous(d[k + 1][0], d[k + 1][1], d[k + 1][2], d[k + 1][3], tolerance))
      return false;
    if (weights[k] > 0.0f && weights[k + 2] > 0.0f &&
        !pair_continuous(d[0][k + 1], d[1][k + 1], d[2][k + 1], d[3][k + 1], tolerance))
      return false;
  }
  return true;
}

float sample_distance(const DistanceCubeMap& map, vec3 dir) {
  float distance = kDistanceInf;
  filter<false>(map, dir, nullptr, &distance, nullptr);
  return distance;
}

}  // namespace proxima
