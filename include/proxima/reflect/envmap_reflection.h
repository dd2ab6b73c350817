// Reflections of a frame through environment maps with distance (Wang et al. 2012): the
// reflector's pixels (rasterized primary visibility) shaded with the shared model, where
// s·L_refl comes from plain, rectified, average-distance or layered env-map lookups
// instead of traced rays. Everything else of the model is evaluated as the reference does.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/reflect/envmap_lookup.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

enum class EnvmapMethod {
  Plain,      // direction lookup (classic environment mapping)
  Rectified,  // §2.2 per-pixel bisection on the distance map
  Average,    // §2.3 average distance d̄ of the whole map
  Layered,    // depth-peeled layered distance map, nearest hit along the ray (replaces §2.4)
  BoxProbe,   // box-projected (parallax-corrected) lookup on a proxy box (reflect/box_probe.h)
};

// "envmap", "rectified", "average", "layered", "boxprobe" (the CLI's --method names).
const char* envmap_method_name(EnvmapMethod method);
// The method whose envmap_method_name is `name`; InputError naming `flag` and listing the
// valid names for anything else.
EnvmapMethod parse_envmap_method(const std::string& name, const char* flag = "--method");

// Objects with a reflective material (specular > 0) on any triangle, in id order.
std::vector<uint32_t> reflective_objects(const Scene& scene);

// Center of the objects' combined bounds: the projection center of their env map.
vec3 projection_center(const Scene& scene, std::span<const uint32_t> objects);

// Largest distance from `center` of a vertex of the objects: every reflection ray starts
// within it (DistanceCubeLayerOptions::viewer_radius).
float viewer_radius(const Scene& scene, std::span<const uint32_t> objects, vec3 center);

// The reflector pixels of a frame: rasterized (raster/) triangle and barycentrics at the
// pixel centers, kept where the visible object is one of `reflectors`.
struct ReflectorPixels {
  ImageU32 triangle;   // 1 channel: triangle id, kNoTriangle where not a reflector pixel
  ImageF barycentric;  // 2 channels: Embree (u, v)
  size_t count = 0;    // reflector pixels
};
ReflectorPixels rasterize_reflector_pixels(const Scene& scene, const Camera& camera,
                                           std::span<const uint32_t> reflectors);

// The maps of one group of reflectors (envmap_groups.h), around the group's center with
// the group's reflectors left out: `map` for Plain / Rectified / Average / BoxProbe (with
// its d̄ for Average), `layers` (render_distance_cube_layers, layer 0 first) for Layered.
// A method's maps may be left empty when it is not run.
struct EnvmapMaps {
  DistanceCubeMap map;
  float average_distance = kDistanceInf;
  std::vector<DistanceCubeMap> layers;
};

// What a method reads: `map` for Plain / Rectified / Average / BoxProbe (with its d̄ for
// Average, `box` for BoxProbe), `layers` (render_distance_cube_layers, layer 0 first) for
// Layered — or, when `groups` is set, per reflector pixel the maps of its object's group:
// groups[group_of[object]] (one map per group of reflectors, envmap_groups.h).
struct EnvmapInputs {
  EnvmapMethod method = EnvmapMethod::Rectified;
  const DistanceCubeMap* map = nullptr;
  float average_distance = kDistanceInf;
  std::span<const DistanceCubeMap> layers;
  std::span<const EnvmapMaps> groups;  // set: the per-group maps replace map, average_distance, layers
  std::span<const uint32_t> group_of;  // per object id, its index in groups (envmap_group_of_objects)
  Bounds3 box;  // BoxProbe: the proxy box (probe_proxy_box)
  RectifyOptions rectify;
  int area_light_samples = 4;  // n×n per area light for the reflector's own direct light
  int glossy_rays = 16;        // lobe samples for gloss > 0 (one lookup each)
  uint64_t seed = 1;           // as the reference: derive_seed(seed, pixel index, 0)
};

struct EnvmapStats {
  size_t pixels = 0;        // reflector pixels shaded
  size_t lookups = 0;       // reflection lookups (pixels × lobe rays)
  size_t map_samples = 0;   // filtered cube-map samples taken by them
  size_t edge_lookups = 0;  // lookups that ended as a miss (edge rule / empty)
  size_t fallback_lookups = 0;  // layered: lookups without a hit that took the rectified one on layer 0
};

struct EnvmapFrame {
  ImageF color;     // 3 channels, linear RGB; reflector pixels only, 0 elsewhere
  ImageU32 object;  // object the pixel's first lookup that found a surface came from;
                    // kNoObject elsewhere and where every lookup missed
  EnvmapStats stats;
};

// One lookup with `inputs.method` from x along dir in the maps `object` reads: its group's
// when `inputs.groups` is set (the object must have one), else the inputs' own.
EnvLookup envmap_lookup(const EnvmapInputs& inputs, uint32_t object, const Environment& env, vec3 x, vec3 dir);

// Throws std::invalid_argument (a caller's error) when `inputs.groups` is set and one of
// `objects` is in no group.
void check_envmap_groups(const EnvmapInputs& inputs, std::span<const uint32_t> objects);

// Shades every reflector pixel of `pixels` (from this camera): L = emission + (1 − s)·ρ·
// (ambient + E/π) with Embree shadows + s·mean over the lobe of the method's lookup.
// Random numbers per pixel as the reference's (k = 1), so the lobe directions and area
// light samples match it. Deterministic for any thread count. `rays` must hold `scene`.
// With `inputs.groups` set, a reflector pixel whose object has no group throws
// std::invalid_argument (a caller's error, checked before shading).
EnvmapFrame shade_reflector_pixels(const Scene& scene, const RayScene& rays, const Camera& camera,
                                   const ReflectorPixels& pixels, const EnvmapInputs& inputs);

}  // namespace proxima
