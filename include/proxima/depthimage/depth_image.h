// DepthImage: one rasterized sample set of a scene — the camera it was taken from and,
// per pixel center, the depth, triangle id, shading normal and direct-lit color of the
// sample (thesis ch. 2: a "reference image" I_i taken with pinhole camera PPC_i).
// A pixel with triangle == kNoTriangle holds no sample.
#pragma once

#include <cstddef>
#include <cstdint>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/scene/scene.h"

namespace proxima {

struct DepthImage {
  Camera camera;     // PPC_i; V_i = camera.position
  ImageF depth;      // 1 channel: −z_cam at the pixel center, +inf where empty
  ImageU32 triangle; // 1 channel: triangle id, kNoTriangle where empty
  ImageF normal;     // 3 channels: unit world shading normal facing the camera, 0 where empty
  ImageF color;      // 3 channels: linear direct light without shadows (RasterOptions::direct_light)
};

// What the sampling functions draw: depth + id always; normal and color only with
// `shade` (metrics need only depth + id). Back faces are culled, as in the thesis
// ("all rendering enables back-face culling"): closed objects never show their insides.
RasterOptions depth_image_raster_options(bool shade);

// Moves rasterized images into a DepthImage of `camera` (normal, color may stay empty).
DepthImage to_depth_image(const Camera& camera, RasterImages&& images);

// Conventional depth image: the nearest front-facing sample per pixel center.
DepthImage render_depth_image(const Scene& scene, const Camera& camera, bool shade);

// Pixels holding a sample.
size_t sample_count(const DepthImage& image);

// World point of the sample at pixel (x, y) (its center, at the stored depth).
// Precondition: the pixel holds a sample.
vec3 sample_point(const DepthImage& image, int x, int y);

// Maps pixel centers + depth of one camera to continuous pixel coordinates + depth of
// another in one affine step (world point = unproject, then project), float.
class Reprojection {
 public:
  Reprojection(const Camera& from, const Camera& to);
  // Pixel (x, y) of `from` at depth d → pixel of `to`; false when the point is not in
  // front of `to` (depth ≤ 0). `out_depth` is −z_cam of `to`.
  // Inline: called per fragment by the pixel-redundancy test and per sample by the metrics.
  bool map(int x, int y, float d, vec2& out_pixel, float& out_depth) const {
    const vec4 u((float(x) + 0.5f) * d, (float(y) + 0.5f) * d, d, 1.0f);
    const float w = glm::dot(row_w_, u);
    if (!(w > 0.0f)) return false;
    out_pixel = vec2(glm::dot(row_x_, u), glm::dot(row_y_, u)) / w;
    out_depth = w;
    return true;
  }
  // map() of four pixels (x[k], y) at depths d[k] at once: bit k of the result is what
  // map() returns for lane k, and where it is set, px[k], py[k] are map()'s out_pixel bit
  // for bit (the same IEEE operations in the same order, in SSE lanes; a loop over map()
  // where SSE2 is missing or the compiler may fuse multiply-adds).
  unsigned map4(const int x[4], int y, const float d[4], float px[4], float py[4]) const;

 private:
  // Rows of the 3×4 map from (x_c·d, y_c·d, d, 1), x_c = x + 0.5, to (X, Y, W) with
  // X/W, Y/W the pixel coordinates in `to` and W its depth.
  vec4 row_x_, row_y_, row_w_;
};

// Pixel of continuous coordinates `p` if it lies in the image, else false.
inline bool pixel_in(const Camera& camera, vec2 p, int& x, int& y) {
  if (!(p.x >= 0.0f && p.y >= 0.0f && p.x < float(camera.width) && p.y < float(camera.height))) return false;
  x = int(p.x);
  y = int(p.y);
  return true;
}

}  // namespace proxima
