// Judging a reflection method against the reference on the same pixels: which pixels are
// compared, which object the reference's mirror ray meets there, and how often a method's
// lookup found that same object.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima {

// A set of pixels: `mask` is 1 channel, 1 where a pixel belongs to the set and 0 elsewhere;
// `pixels` is the number of 1s.
struct PixelMask {
  ImageU8 mask;
  size_t pixels = 0;
};

// Pixels both the method's own visibility (`triangles`, 1 channel, kNoTriangle where the
// method sees no reflector) and the reference's item buffer give to a triangle of one of
// `reflectors` (object ids). `triangles` and `item` have the same size.
PixelMask comparison_mask(const ImageU32& triangles, const ItemBuffer& item, const Scene& scene,
                          std::span<const uint32_t> reflectors);

// Per pixel of `mask`, the object the reference's mirror ray from the primary hit (`item`)
// meets, kNoObject where it escapes and elsewhere: what a reflection method's lookup should
// have found. The ray starts at the reference's offset origin (DirectLight::offset_origin).
// `rays` must hold `scene`; deterministic for any thread count.
ImageU32 reference_reflected_objects(const Scene& scene, const RayScene& rays, const Camera& camera,
                                     const ItemBuffer& item, const ImageU8& mask);

// `compared` without the pixels whose reference mirror ray meets one of `reflectors`: a
// map of the environment with the reflectors left out cannot show self-reflections.
PixelMask environment_mask(const PixelMask& compared, const ImageU32& reference_objects,
                           std::span<const uint32_t> reflectors);

// Percentage of the pixels of `mask` where `objects` (a method's looked-up object per pixel)
// equals `reference_objects`; 100 when the mask is empty.
double object_match_pct(const ImageU32& objects, const ImageU32& reference_objects, const PixelMask& mask);

}  // namespace proxima
