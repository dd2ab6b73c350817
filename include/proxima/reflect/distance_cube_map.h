// Distance cube map (Wang et al. 2012, "Environment mapping with position rectification",
// §2.1): a cube environment map seen from a projection center c whose texels hold the
// radiance of the environment surface (RGB) and, in the alpha channel, that surface's
// Euclidean distance to c; d_inf (+inf here) where nothing is hit. Rendered with the
// software rasterizer (raster/), one 90° face camera per face (core/cube_camera.h);
// texels are shaded with the reference's local model (trace/direct_light.h).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

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
  // Layered maps (render_distance_cube_layers), layers ≥ 1: texels the peel found but left
  // empty because no ray from the viewer sphere can reach them (0 for a single map).
  size_t hidden_texels = 0;
  size_t shaded_texels = 0;  // texels shaded (covered and stored)
  float min_distance = kDistanceInf;  // smallest stored distance (kDistanceInf when empty)
};

struct DistanceCubeMapOptions {
  int resolution = 512;        // texels per face side
  int area_light_samples = 4;  // n of the n×n area-light samples per texel (as the reference)
  uint64_t seed = 1;           // texel streams: derive_seed(seed, face, texel index)
  // What to draw (at most one non-empty; both empty = the whole scene):
  std::span<const uint32_t> objects;  // only these object ids
  std::span<const uint32_t> exclude;  // every object but these (e.g. the reflector itself)
  // Texel radiance of triangle (u, v) seen along `toward_viewer` (from the surface to c);
  // unset = the reference's local model with shadows (DirectLight). The cluster method's
  // comparison sets its unshadowed shading so both methods show the same surfaces' colors.
  std::function<vec3(uint32_t triangle, float u, float v, vec3 toward_viewer)> shade;
};

// Renders the six faces around `center`. `rays` must hold `scene` (shadow rays see every
// object, including excluded ones: the reflector still casts shadows on its environment).
// Near plane 1e-4 × scene diagonal, far plane 4 × diagonal. Throws InputError for a
// resolution outside 1..kMaxImageSide.
DistanceCubeMap render_distance_cube_map(const Scene& scene, const RayScene& rays, vec3 center,
                                         const DistanceCubeMapOptions& options);

// Layered distance map (Szirmay-Kalos, Aszódi, Lazányi, Premecz 2005, "Approximate
// ray-tracing on the GPU with distance impostors"; Umenhoffer, Patow, Szirmay-Kalos 2007,
// "Robust multiple specular reflections and refractions", GPU Gems 3 ch. 17): the cube map
// depth-peeled from c (raster/depth_peeling.h). Layer 0 is the ordinary distance map;
// layer k holds, per texel, the nearest surface behind layer k − 1's along the same
// direction from c. A bounded number of layers, whatever the number of objects.
struct DistanceCubeLayerOptions {
  int layers = 3;  // K, in 1..kMaxDistanceCubeLayers: layer 0 plus K − 1 peels
  // r: every ray looked up starts within r of c (the reflectors' bounding sphere about c).
  float viewer_radius = 0.0f;
  // Layers ≥ 1 skip triangles whose plane has the whole viewer sphere on its back side: a
  // ray from the sphere meets them from behind, which on a closed mesh is never its first
  // hit (the mesh's front faces come first). Spares the layers the backs of walls.
  bool cull_back_faces = true;
  // Layers ≥ 1 shade only texels a ray from the viewer sphere can reach: a ray from within r
  // of c gets behind layer k − 1 only across one of its depth discontinuities (silhouettes,
  // holes), and its points at distance ρ > r from c lie within asin(r/ρ) of its end
  // direction as seen from c. Texels farther than that from every discontinuity of layer
  // k − 1 are left empty (counted in hidden_texels); tiles of 16² texels, tested by angle.
  bool reachable_only = true;
  // Relative depth step between neighbouring texels that counts as a discontinuity.
  float edge_jump = 0.02f;
  // Peeling: a surface within this relative depth of the previous layer counts as the same
  // surface (coplanar duplicates, decals) and is skipped (DepthPeelOptions::min_separation).
  float min_separation = 1e-3f;
};
inline constexpr int kMaxDistanceCubeLayers = 16;

// Layers 0 … K − 1 around `center` (each as render_distance_cube_map, with the same
// objects/exclude, shading and texel seeds: layer 0 is bit-identical to the single map).
// Fewer than K when a layer comes out empty. Deterministic for any thread count. Throws
// InputError for a resolution outside 1..kMaxImageSide or a layer count outside
// 1..kMaxDistanceCubeLayers.
std::vector<DistanceCubeMap> render_distance_cube_layers(const Scene& scene, const RayScene& rays, vec3 center,
                                                         const DistanceCubeMapOptions& options,
                                                         const DistanceCubeLayerOptions& layers);

// One filtered lookup along a direction from c.
struct CubeSample {
  vec3 color{0.0f};               // bilinear over the non-empty taps (weights renormalized); 0 if empty
  float distance = kDistanceInf;  // the same filter on the distance; kDistanceInf if empty
  uint32_t object = 0xFFFFFFFFu;  // object of the heaviest non-empty tap (kNoObject if empty)
  bool empty = true;              // the non-empty taps carry less than half the weight
  // Smallest and largest distance among the non-empty taps of positive weight: a large
  // spread means the filter straddles a silhouette (kDistanceInf, 0 if empty).
  float tap_min = kDistanceInf, tap_max = 0.0f;
  bool one_object = false;  // those taps all show the same object
};

// Bilinear lookup of direction `dir` (need not be unit; 0 or NaN → empty) with seams: a tap beyond a
// face edge is the texel of the neighbouring face that the tap's (extrapolated) center
// direction falls in, so filtering is continuous across edges and corners. Empty texels
// never blend into colors or distances; coverage is decided as by the nearest tap (≥ half
// the weight non-empty), so silhouettes stay as sharp as the texel grid.
CubeSample sample_cube(const DistanceCubeMap& map, vec3 dir);

// The bilinear taps of `dir` grouped by the object they show; of those objects, the one
// whose own filtered distance (weights renormalized over its taps) is closest to `rho`,
// as a sample of that object alone (one_object = true, tap_min/tap_max its taps' range).
// Where the taps straddle two objects it tells whether a point at distance rho along
// `dir` lies on one of their surfaces. Empty when every tap is empty (0 or NaN dir too).
CubeSample sample_cube_surface(const DistanceCubeMap& map, vec3 dir, float rho);

// The bilinear taps of `dir` that show `object`, weights renormalized over them: that
// object's surface alone (one_object = true, tap_min/tap_max its taps' range). Empty
// when its taps carry less than half the weight (the coverage rule of sample_cube).
CubeSample sample_cube_object(const DistanceCubeMap& map, vec3 dir, uint32_t object);

// Whether the bilinear taps of `dir` (those of positive weight) lie on one continuous
// surface: across each pair of neighbouring taps, the distances extrapolated from the
// texels beyond either tap meet within `tolerance` plus half the two slopes' difference —
// true on a plane or a crease even where it is seen at a grazing angle (neighbouring
// texels far apart in distance, other objects), false across a silhouette's step. Reads
// the 4×4 texels around the taps (across face edges as sample_cube). False if a tap is empty.
bool cube_taps_continuous(const DistanceCubeMap& map, vec3 dir, float tolerance);

// sample_cube(map, dir).distance (up to rounding) without the color, from the compact
// distance planes (the bisection's inner steps). A zero or NaN dir is empty.
float sample_distance(const DistanceCubeMap& map, vec3 dir);

}  // namespace proxima
