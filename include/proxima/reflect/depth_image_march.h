// Intersection of a ray segment with a depth image (thesis ch. 4 §4.5, Algorithm 7): the
// segment is projected into the depth image's camera and marched one texel at a time, the
// ray depth at each step interpolated perspective-correctly (1/z linear in screen space,
// the k1, k2 form of Algorithm 7).
#pragma once

#include <optional>

#include "proxima/core/camera.h"
#include "proxima/core/camera_projection.h"
#include "proxima/core/image.h"

namespace proxima {

struct DepthImageHit {
  vec2 pixel;           // continuous pixel coordinates of the hit in the depth image
  float depth;          // −z_cam of the hit (the stored surface depth there)
  bool filled = false;  // no crossing: the surface the ray was last in front of before it
                        // went behind a nearer one (MarchOptions::fill_behind)
};

struct MarchOptions {
  // Neighbouring texels belong to one surface when their depths differ by at most this
  // fraction; across a larger jump (a silhouette) a ray found behind the nearer texel
  // passes behind it instead of hitting it.
  float continuity = 0.1f;
  // A ray that goes behind a nearer surface and never comes out again hit something the
  // image does not hold. With fill_behind it returns the surface it was last in front of
  // (the background at the silhouette, flagged `filled`) instead of nothing.
  bool fill_behind = false;
  // Optional depth_block_min(depth, block) of the same depth image: runs of steps inside one
  // block that stay in front of its nearest texel are skipped. The result is identical.
  const ImageF* block_min = nullptr;
  int block = 8;
  // Four steps at a time where SSE2 is available (runs that only move on are passed in one
  // check); false marches one step at a time. The result is identical.
  bool batch = true;
  // > 1: `depth` is depth_block_min(image, coarse) of the camera's image, one texel per
  // coarse × coarse block (nearest depth), and the march steps over it; hit pixels are
  // returned in the camera's pixel coordinates. An approximation: surfaces are taken at
  // their block's nearest depth and silhouettes grow by up to a block.
  int coarse = 1;
};

// Per block × block tile of `depth` (1 channel) the minimum depth; ceil(w / block) × ceil(h / block).
ImageF depth_block_min(const ImageF& depth, int block);

// First hit of the segment begin → end with the surface stored in `depth` (1 channel,
// camera.width × camera.height, −z_cam, +inf where empty), seen from `camera`.
// A hit is a step where the ray goes from in front of the stored surface to behind it;
// a ray that appears behind a surface across a silhouette passes behind it. Parts of the
// segment outside the image are skipped. Both ends must be in front of the camera
// (depth > 0), else nullopt; nullopt when nothing is hit (see fill_behind).
std::optional<DepthImageHit> march_depth_image(const Camera& camera, const ImageF& depth, vec3 begin, vec3 end,
                                               const MarchOptions& options = {});
// The same with the camera's projection constants computed once (many rays of one camera).
std::optional<DepthImageHit> march_depth_image(const CameraProjection& camera, const ImageF& depth, vec3 begin,
                                               vec3 end, const MarchOptions& options = {});

}  // namespace proxima
