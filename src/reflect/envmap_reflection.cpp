// Reflector shading through environment maps with distance — Wang, Tang, Sun, Ma,
// "Environment mapping with position rectification", J. Image and Graphics 17(3), 2012
// (papers/000_…, line 188), Fig. 1's per-pixel stage.
//
// Paper symbol ↔ variable:
//   x     the reflector's surface point at a pixel      sp.p
//   l̂     reflected view direction (mirror or a lobe ray) dir passed to lookup()
//   L_env the environment map (with distance in alpha)  inputs.map / inputs.layers[i].map
// The paper shades mirrors only (s = 1, no shadows); here the lookup replaces the reference's
// reflected radiance L_refl inside the shared model, so s < 1 blends and glossy lobes work
// as in docs/shading.md (one lookup per lobe ray).
#include "proxima/reflect/envmap_reflection.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/box_probe.h"
#include "proxima/trace/direct_light.h"
#include "proxima/scene/shading.h"

namespace proxima {
namespace {

constexpr int kTileSize = 16;

// The maps one reflector pixel reads: the inputs' own, or its object's group's.
struct PixelMaps {
  const DistanceCubeMap* map = nullptr;
  float average_distance = kDistanceInf;
  std::span<const DistanceCubeMap> layers;
};

PixelMaps maps_of(const EnvmapInputs& in, uint32_t object) {
  if (in.groups.empty()) return {in.map, in.average_distance, in.layers};
  const EnvmapMaps& g = in.groups[in.group_of[object]];
  return {&g.map, g.average_distance, g.layers};
}

bool has_group(const EnvmapInputs& in, uint32_t object) {
  return object < in.group_of.size() && in.group_of[object] < in.groups.size();
}

[[noreturn]] void fail_group(const char* caller, uint32_t object) {
  throw std::invalid_argument(std::string(caller) + ": reflector object " + std::to_string(object) +
                              " is in no env-map group");
}

// With per-group maps, every reflector pixel's object must have a group.
void check_groups(const Scene& scene, const ReflectorPixels& pixels, const EnvmapInputs& in) {
  if (in.groups.empty()) return;
  for (uint32_t t : pixels.triangle.data()) {
    if (t == kNoTriangle) continue;
    const uint32_t o = scene.triangle_object[t];
    if (!has_group(in, o)) fail_group("shade_reflector_pixels", o);
  }
}

EnvLookup lookup(const EnvmapInputs& in, const PixelMaps& m, const Environment& env, vec3 x, vec3 dir) {
  switch (in.method) {
    case EnvmapMethod::Plain:
      return plain_lookup(*m.map, env, dir);
    case EnvmapMethod::Rectified:
      return rectified_lookup(*m.map, env, x, dir, in.rectify);
    case EnvmapMethod::Average:
      return average_lookup(*m.map, env, x, dir, m.average_distance);
    case EnvmapMethod::Layered:
      return layered_lookup(m.layers, env, x, dir, in.rectify);
    case EnvmapMethod::BoxProbe:
      return box_probe_lookup(*m.map, env, x, dir, in.box);
  }
  return {};
}

}  // namespace

EnvLookup envmap_lookup(const EnvmapInputs& inputs, uint32_t object, const Environment& env, vec3 x, vec3 dir) {
  return lookup(inputs, maps_of(inputs, object), env, x, dir);
}

void check_envmap_groups(const EnvmapInputs& inputs, std::span<const uint32_t> objects) {
  if (inputs.groups.empty()) return;
  for (uint32_t o : objects)
    if (!has_group(inputs, o)) fail_group("env-map lookup", o);
}

const char* envmap_method_name(EnvmapMethod method) {
  switch (method) {
    case EnvmapMethod::Plain:
      return "envmap";
    case EnvmapMethod::Rectified:
      return "rectified";
    case EnvmapMethod::Average:
      return "average";
    case EnvmapMethod::Layered:
      return "layered";
    case EnvmapMethod::BoxProbe:
      return "boxprobe";
  }
  return "?";
}

EnvmapMethod parse_envmap_method(const std::string& name, const char* flag) {
  for (EnvmapMethod m : {EnvmapMethod::Plain, EnvmapMethod::Rectified, EnvmapMethod::Average, EnvmapMethod::Layered,
                         EnvmapMethod::BoxProbe})
    if (name == envmap_method_name(m)) return m;
  fail_input(std::string(flag) + ": unknown env-map method '" + name +
             "' (envmap, rectified, average, layered, boxprobe)");
}

std::vector<uint32_t> reflective_objects(const Scene& scene) {
  std::vector<uint32_t> out;
  for (uint32_t o = 0; o < uint32_t(scene.objects.size()); ++o) {
    const Object& obj = scene.objects[o];
    for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t)
      if (scene.materials[scene.triangle_material[t]].reflective()) {
        out.push_back(o);
        break;
      }
  }
  return out;
}

vec3 projection_center(const Scene& scene, std::span<const uint32_t> objects) {
  Bounds3 b;
  for (uint32_t o : objects) b.extend(object_bounds(scene, o));
  return b.center();
}

float viewer_radius(const Scene& scene, std::span<const uint32_t> objects, vec3 center) {
  float r = 0.0f;
  for (uint32_t o : objects) {
    const Object& obj = scene.objects[o];
    for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t)
      for (int k = 0; k < 3; ++k) r = std::max(r, glm::length(scene.positions[scene.triangles[t][k]] - center));
  }
  return r;
}

ReflectorPixels rasterize_reflector_pixels(const Scene& scene, const Camera& camera,
                                           std::span<const uint32_t> reflectors) {
  RasterOptions ro;
  ro.outputs = kRasterDepthId | kRasterBarycentric | kRasterObject;
  RasterImages g = rasterize(scene, camera, ro);
  ReflectorPixels out{std::move(g.triangle), std::move(g.barycentric), 0};
  for (size_t i = 0; i < g.object.data().size(); ++i) {
    const uint32_t o = g.object.data()[i];
    if (std::find(reflectors.begin(), reflectors.end(), o) != reflectors.end())
      ++out.count;
    else
      out.triangle.data()[i] = kNoTriangle;
  }
  return out;
}

EnvmapFrame shade_reflector_pixels(const Scene& scene, const RayScene& rays, const Camera& camera,
                                   const ReflectorPixels& pixels, const EnvmapInputs& in) {
  const int w = camera.width, h = camera.height;
  EnvmapFrame frame{ImageF(w, h, 3, 0.0f), ImageU32(w, h, 1, kNoObject), {}};
  check_groups(scene, pixels, in);
  const DirectLight light(scene, rays, in.area_light_samples);
  std::atomic<size_t> n_pixels{0}, n_lookups{0}, n_samples{0}, n_edges{0}, n_fallbacks{0};
  parallel_for_tiles(w, h, kTileSize, [&](const Tile& tile) {
    std::vector<vec2> lobe(size_t(in.glossy_rays));
    size_t tp = 0, tl = 0, ts = 0, te = 0, tf = 0;
    uint32_t first_object = kNoObject;
    PixelMaps maps;
    auto trace = [&](vec3 x, vec3 dir) {
      EnvLookup r = lookup(in, maps, scene.environment, x, dir);
      if (first_object == kNoObject && !r.miss) first_object = r.object;
      ++tl;
      ts += size_t(r.steps);
      te += r.miss;
      tf += r.fallback;
      return r.color;
    };
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const uint32_t t = pixels.triangle.at(x, y);
        if (t == kNoTriangle) continue;
        ++tp;
        first_object = kNoObject;
        maps = maps_of(in, scene.triangle_object[t]);
        const float u = pixels.barycentric.at(x, y, 0), v = pixels.barycentric.at(x, y, 1);
        const vec3 view = triangle_point(scene, t, u, v) - camera.position;
        SurfacePoint sp = surface_point_seen(scene, t, u, v, view);
        // The reference's stream for this pixel (k = 1): area-light jitter, then the lobe.
        Pcg32 rng(derive_seed(in.seed, uint64_t(y) * uint64_t(w) + uint64_t(x), 0));
        ShadingTerms terms = light.local_terms(sp, rng);
        const Material& m = scene.materials[scene.triangle_material[t]];
        if (m.specular > 0.0f) {
          const vec3 mirror = reflect(glm::normalize(view), sp.n);
          const float half_angle = glossy_lobe_half_angle(m.gloss);
          if (half_angle > 0.0f) {
            stratified_samples_2d(lobe, rng);
            vec3 sum(0.0f);
            for (vec2 s : lobe) sum += trace(sp.p, glossy_lobe_direction(mirror, sp.ng, half_angle, s));
            terms.reflected = sum / float(lobe.size());
          } else {
            terms.reflected = trace(sp.p, glossy_lobe_direction(mirror, sp.ng, 0.0f, vec2(0.0f)));
          }
        }
        const vec3 color = combine_shading(terms);
        for (int c = 0; c < 3; ++c) frame.color.at(x, y, c) = color[c];
        frame.object.at(x, y) = first_object;
      }
    n_pixels += tp;
    n_lookups += tl;
    n_samples += ts;
    n_edges += te;
    n_fallbacks += tf;
  });
  frame.stats = {n_pixels.load(), n_lookups.load(), n_samples.load(), n_edges.load(), n_fallbacks.load()};
  return frame;
}

}  // namespace proxima
