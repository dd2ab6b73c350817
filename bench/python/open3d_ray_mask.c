/* LD_PRELOAD shim for bench/python/rays_vs_open3d.py: sets the ray mask of every ray Open3D
 * hands to Embree's stream queries (rtcIntersect1M, rtcOccluded1M) to all ones, then calls
 * Embree's own function.
 *
 * Why: Debian 12's Embree 3.13 is built with EMBREE_RAY_MASK on, and Open3D 0.16's
 * RaycastingScene never sets RTCRay::mask (it stays 0), so every ray misses every geometry
 * (whose mask is all ones). Open3D has no API to set it. proxima calls rtcIntersect1/16 and
 * rtcOccluded1 only, so the shim touches Open3D's queries alone; its cost is one store per
 * ray, added to Open3D's time.
 *
 * Embree is looked up in the library already loaded (RTLD_NOLOAD): Python loads Open3D's
 * extension with RTLD_LOCAL, so RTLD_NEXT would not find it.
 *
 *   cc -O2 -shared -fPIC -o open3d_ray_mask.so open3d_ray_mask.c -ldl
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <embree3/rtcore.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

typedef void (*intersect_fn)(RTCScene, struct RTCIntersectContext*, struct RTCRayHit*, unsigned int, size_t);
typedef void (*occluded_fn)(RTCScene, struct RTCIntersectContext*, struct RTCRay*, unsigned int, size_t);

static void* embree_function(const char* name) {
  void* embree = dlopen("libembree3.so.3", RTLD_LAZY | RTLD_NOLOAD);
  void* f = embree ? dlsym(embree, name) : NULL;
  if (!f) {
    fprintf(stderr, "open3d_ray_mask: %s not found in the loaded libembree3.so.3\n", name);
    abort();
  }
  return f;
}

void rtcIntersect1M(RTCScene scene, struct RTCIntersectContext* context, struct RTCRayHit* rays, unsigned int m,
                    size_t stride) {
  static intersect_fn cached;  /* threads may race to fill it: atomics, same value */
  intersect_fn embree = __atomic_load_n(&cached, __ATOMIC_ACQUIRE);
  if (!embree) __atomic_store_n(&cached, embree = (intersect_fn)embree_function("rtcIntersect1M"), __ATOMIC_RELEASE);
  for (unsigned int i = 0; i < m; ++i) ((struct RTCRayHit*)((char*)rays + i * stride))->ray.mask = 0xFFFFFFFFu;
  embree(scene, context, rays, m, stride);
}

void rtcOccluded1M(RTCScene scene, struct RTCIntersectContext* context, struct RTCRay* rays, unsigned int m,
                   size_t stride) {
  static occluded_fn cached;
  occluded_fn embree = __atomic_load_n(&cached, __ATOMIC_ACQUIRE);
  if (!embree) __atomic_store_n(&cached, embree = (occluded_fn)embree_function("rtcOccluded1M"), __ATOMIC_RELEASE);
  for (unsigned int i = 0; i < m; ++i) ((struct RTCRay*)((char*)rays + i * stride))->mask = 0xFFFFFFFFu;
  embree(scene, context, rays, m, stride);
}
