// Distance cube map (Wang et al. 2012, "Environment mapping with position rectification",
// §2.1): a cube environment map seen from a projection center c whose texels hold the
// radiance of the environment surface (RGB) and, in the alpha channel, that surface's
// Euclidean distance to c; d_inf (+inf here) where nothing is hit. Rendered with the
// software rasterizer (raster/), one 90° face camera per face (core/cube_camera.h);
// texels are shaded with the reference's local model (trace/direct_light.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "proxima/core/cube_camera.h"
#include "proxima/core/image.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

// The paper's d_inf: larger than every environment distance.
inline constexpr float kDistanceInf = kInf;

struct DistanceCubeMap {
  CubeCamera camera;                // projection center c, face resolution, near/far
  std::array<Camera, 6> face_cams;  // face_cameras(camera), cached for seam lookups
  // Per face: camera_right, camera_up, camera_forward of face_cams (cached for lookups).
  std::array<std::array<vec3, 3>, 6> face_basis;
  // Per face (CubeFace order): 4 channels — linear RGB radiance of the surface, Euclidean
  // distance to c (kDistanceInf where empty). An empty image = nothing on that face.
  std::array<ImageF, 6> faces;
  std::array<ImageU32, 6> objects;  // object id per texel (kNoObject = 0xFFFFFFFF where empty)
  // The alpha channel of `faces` again, 1 channel: the bisection reads only distances, and
  // a quarter of the bytes keeps more of the map in cache.
  std::array<ImageF, 6> distances;
  double covered_fraction = 0.0;  // texels hit / all texels (a solid-angle proxy)
};

struct DistanceCubeMapOptions {
  int resolution = 512;        // texels per face side
  int area_light_samples = 4;  // n of the n×n area-light samples per texel (as the reference)
  uint64_t seed = 1;           // texel streams: derive_seed(seed, face, texel index)
  // What to draw (at most one non-empty; both empty = the whole scene):
  std::span<const uint32_t> objects;  // only these object ids
  std::span<const uint32_t> exclude;  // every object but these (e.g. the reflector itself)
};

// Renders the six faces around `center`. `rays` must hold `scene` (shadow rays see every
// object, including excluded ones: the reflector still casts shadows on its environment).
// Near plane 1e-4 × scene diagonal, far plane 4 × diagonal. Throws InputError for a
// resolution outside 1..kMaxImageSide.
DistanceCubeMap render_distance_cube_map(const Scene& scene, const RayScene& rays, vec3 center,
                                         const DistanceCubeMapOptions& options);

// One filtered lookup along a direction from c.
struct CubeSample {
  vec3 color{0.0f};               // bilinear over the non-empty taps (weights renormalized); 0 if empty
  float distance = kDistanceInf;  // the same filter on the distance; kDistanceInf if empty
  uint32_t object = 0xFFFFFFFFu;  // object of the heaviest non-empty tap (kNoObject if empty)
  bool empty = true;              // the non-empty taps carry less than half the weight
};

// Bilinear lookup of direction `dir` (need not be unit; 0 or NaN → empty) with seams: a tap beyond a
// face edge is the texel of the neighbouring face that the tap's (extrapolated) center
// direction falls in, so filtering is continuous across edges and corners. Empty texels
// never blend into colors or distances; coverage is decided as by the nearest tap (≥ half
// the weight non-empty), so silhouettes stay as sharp as the texel grid.
CubeSample sample_cube(const DistanceCubeMap& map, vec3 dir);

// sample_cube(map, dir).distance (up to rounding) without the color, from the compact
// distance planes (the bisection's inner steps). A zero or NaN dir is empty.
float sample_distance(const DistanceCubeMap& map, vec3 dir);

}  // namespace proxima
