#include "proxima/reflect/reflection_comparison.h"

#include <algorithm>

#include "proxima/core/parallel.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/scene/shading.h"
#include "proxima/trace/direct_light.h"

namespace proxima {

namespace {

bool is_one_of(std::span<const uint32_t> ids, uint32_t id) { return std::find(ids.begin(), ids.end(), id) != ids.end(); }

}  // namespace

PixelMask comparison_mask(const ImageU32& triangles, const ItemBuffer& item, const Scene& scene,
                          std::span<const uint32_t> reflectors) {
  PixelMask out{ImageU8(triangles.width(), triangles.height(), 1, 0), 0};
  for (size_t i = 0; i < out.mask.data().size(); ++i) {
    const uint32_t t = item.triangle.data()[i];
    if (triangles.data()[i] == kNoTriangle || t == kNoTriangle) continue;
    if (!is_one_of(reflectors, scene.triangle_object[t])) continue;
    out.mask.data()[i] = 1;
    ++out.pixels;
  }
  return out;
}

ImageU32 reference_reflected_objects(const Scene& scene, const RayScene& rays, const Camera& camera,
                                     const ItemBuffer& item, const ImageU8& mask) {
  ImageU32 out(camera.width, camera.height, 1, kNoObject);
  const DirectLight offsets(scene, rays, 1);
  parallel_for(size_t(camera.height), 8, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < camera.width; ++x) {
        if (!mask.at(x, y)) continue;
        const uint32_t t = item.triangle.at(x, y);
        const float u = item.barycentric.at(x, y, 0), v = item.barycentric.at(x, y, 1);
        const vec3 view = triangle_point(scene, t, u, v) - camera.position;
        const SurfacePoint sp = surface_point_seen(scene, t, u, v, view);
        const vec3 dir = glossy_lobe_direction(reflect(glm::normalize(view), sp.n), sp.ng, 0.0f, vec2(0.0f));
        const Hit hit = rays.intersect(Ray{offsets.offset_origin(sp), dir, 0.0f, kInf});
        if (hit.valid()) out.at(x, y) = scene.triangle_object[hit.triangle];
      }
  });
  return out;
}

PixelMask environment_mask(const PixelMask& compared, const ImageU32& reference_objects,
                           std::span<const uint32_t> reflectors) {
  PixelMask out = compared;
  for (size_t i = 0; i < out.mask.data().size(); ++i)
    if (out.mask.data()[i] && is_one_of(reflectors, reference_objects.data()[i])) {
      out.mask.data()[i] = 0;
      --out.pixels;
    }
  return out;
}

double object_match_pct(const ImageU32& objects, const ImageU32& reference_objects, const PixelMask& mask) {
  size_t same = 0;
  for (size_t i = 0; i < mask.mask.data().size(); ++i)
    same += mask.mask.data()[i] && objects.data()[i] == reference_objects.data()[i];
  return mask.pixels ? 100.0 * double(same) / double(mask.pixels) : 100.0;
}

}  // namespace proxima
