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

DistanceCubeMap render_distance_cube_map(const Scene& scene, const RayScene& rays, vec3 center,
                                         const DistanceCubeMapOptions& options) {
  static_assert(kMaxImageSide == 16384);
  if (options.resolution < 1 || options.resolution > kMaxImageSide)
    fail_input("distance cube map: resolution must be in 1..16384");
  const float diagonal = std::max(scene_bounds(scene).diagonal(), 1e-3f);
  DistanceCubeMap map;
  map.camera = CubeCamera{center, options.resolution, 1e-4f * diagonal, 4.0f * diagonal};
  map.face_cams = face_cameras(map.camera);
  for (size_t f = 0; f < 6; ++f)
    map.face_basis[f] = {camera_right(map.face_cams[f]), camera_up(map.face_cams[f]),
                         camera_forward(map.face_cams[f])};

  const std::vector<uint32_t> objects = draw_list(scene, options);
  const std::vector<Bounds3> bounds = raster_object_bounds(scene);
  RasterOptions ro;
  ro.outputs = kRasterDepthId | kRasterBarycentric | kRasterObject;
  ro.objects = objects;
  ro.object_bounds = bounds;
  const DirectLight light(scene, rays, options.area_light_samples);
  const int res = options.resolution;
  size_t covered = 0;
  RasterImages g;
  for (int f = 0; f < 6; ++f) {
    if (objects.empty()) break;
    rasterize(scene, map.face_cams[size_t(f)], ro, g, AcceptAllFragments{});
    size_t face_covered = 0;
    for (uint32_t t : g.triangle.data()) face_covered += t != kNoTriangle;
    if (face_covered == 0) continue;  // leave the face empty: no memory for layers that miss it
    covered += face_covered;
    ImageF& face = map.faces[size_t(f)];
    face = ImageF(res, res, 4, 0.0f);
    ImageF& distance = map.distances[size_t(f)];
    distance = ImageF(res, res, 1, kDistanceInf);
    map.objects[size_t(f)] = g.object;
    parallel_for_tiles(res, res, kTileSize, [&](const Tile& tile) {
      for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
          const uint32_t t = g.triangle.at(x, y);
          if (t == kNoTriangle) {
            face.at(x, y, 3) = kDistanceInf;
            continue;
          }
          vec3 p = triangle_point(scene, t, g.barycentric.at(x, y, 0), g.barycentric.at(x, y, 1));
          SurfacePoint sp =
              surface_point_seen(scene, t, g.barycentric.at(x, y, 0), g.barycentric.at(x, y, 1), p - center);
          Pcg32 rng(derive_seed(options.seed, uint64_t(f), uint64_t(y) * uint64_t(res) + uint64_t(x)));
          // Texels are one bounce deep: their own reflections are beyond the bounce limit.
          vec3 color = combine_shading(light.local_terms(sp, rng));
          for (int c = 0; c < 3; ++c) face.at(x, y, c) = color[c];
          face.at(x, y, 3) = distance.at(x, y) = glm::length(p - center);
        }
    });
  }
  map.covered_fraction = double(covered) / (6.0 * double(res) * double(res));
  return map;
}

namespace {

// Bilinear filter of `dir` over the non-empty texels; with kColor false only the distance.
// Returns the covered weight (the sum of the non-empty taps' weights).
template <bool kColor>
float filter(const DistanceCubeMap& map, vec3 dir, vec3* color, float* distance, uint32_t* object) {
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
  const int res = map.camera.resolution;
  const float half = 0.5f * float(res);
  const float depth = glm::dot(dir, basis[2]);  // ≥ |dir|/√3 on the chosen face
  if (!(depth > 0.0f)) return 0.0f;             // dir = 0 or NaN: nothing to look up
  const float scale = half / depth;
  // Bilinear taps around the continuous position (texel centers at +0.5).
  const float fx = half + glm::dot(dir, basis[0]) * scale - 0.5f;
  const float fy = half - glm::dot(dir, basis[1]) * scale - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float ax = fx - float(x0), ay = fy - float(y0);
  const float weights[4] = {(1 - ax) * (1 - ay), ax * (1 - ay), (1 - ax) * ay, ax * ay};
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
    covered += weights[k];
    d_sum += weights[k] * d;
    if constexpr (kColor) {
      c_sum += weights[k] * vec3(texel[0], texel[1], texel[2]);
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

}  // namespace

CubeSample sample_cube(const DistanceCubeMap& map, vec3 dir) {
  CubeSample s;
  uint32_t object = s.object;
  vec3 color(0.0f);
  float distance = kDistanceInf;
  if (filter<true>(map, dir, &color, &distance, &object) < 0.5f) return s;
  s.empty = false;
  s.color = color;
  s.distance = distance;
  s.object = object;
  return s;
}

float sample_distance(const DistanceCubeMap& map, vec3 dir) {
  float distance = kDistanceInf;
  filter<false>(map, dir, nullptr, &distance, nullptr);
  return distance;
}

}  // namespace proxima
