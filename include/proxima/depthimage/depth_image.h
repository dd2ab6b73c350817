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

// SSE lanes give map()'s bits only if the scalar map() is not contracted into FMAs.
#if defined(__SSE2__) && !defined(__FMA__)
#define PROXIMA_REPROJECT_SSE 1
#include <emmintrin.h>
#endif

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

// Pixel of continuous coordinates `p` if it lies in the image, else false.
inline bool pixel_in(int width, int height, vec2 p, int& x, int& y) {
  if (!(p.x >= 0.0f && p.y >= 0.0f && p.x < float(width) && p.y < float(height))) return false;
  x = int(p.x);
  y = int(p.y);
  return true;
}
inline bool pixel_in(const Camera& camera, vec2 p, int& x, int& y) {
  return pixel_in(camera.width, camera.height, p, x, y);
}

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
  unsigned map4(const int x[4], int y, const float d[4], float px[4], float py[4]) const {
#ifdef PROXIMA_REPROJECT_SSE
    __m128 X = _mm_setzero_ps(), Y = X;  // set by lanes(); the init quiets -Wmaybe-uninitialized
    const __m128 ok = lanes(x, y, d, X, Y);
    _mm_storeu_ps(px, X);
    _mm_storeu_ps(py, Y);
    return unsigned(_mm_movemask_ps(ok));
#else
    unsigned ok = 0;
    for (int k = 0; k < 4; ++k) {
      vec2 p(0.0f);
      float depth;
      if (map(x[k], y, d[k], p, depth)) ok |= 1u << k;
      px[k] = p.x;
      py[k] = p.y;
    }
    return ok;
#endif
  }
  // map4() then pixel_in() on a width × height image (sides ≤ kMaxImageSide): bit k set
  // iff lane k lands in it, and then at[k] = ry·width + rx is its pixel (else 0). For the
  // pixel-redundancy run test: the coordinates never leave the SSE registers.
  unsigned pixel4(const int x[4], int y, const float d[4], int width, int height, uint32_t at[4]) const {
#ifdef PROXIMA_REPROJECT_SSE
    __m128 X = _mm_setzero_ps(), Y = X;  // set by lanes(); the init quiets -Wmaybe-uninitialized
    const __m128 ok = lanes(x, y, d, X, Y);  // before X, Y are read (argument order is unspecified)
    const __m128 zero = _mm_setzero_ps();
    const __m128 in = _mm_and_ps(
        _mm_and_ps(ok, _mm_and_ps(_mm_cmpge_ps(X, zero), _mm_cmpge_ps(Y, zero))),
        _mm_and_ps(_mm_cmplt_ps(X, _mm_set1_ps(float(width))), _mm_cmplt_ps(Y, _mm_set1_ps(float(height)))));
    // Truncation = int() of pixel_in(); outside lanes become pixel (0, 0). Both < 2^15,
    // so ry·width + rx is one 16-bit multiply-add per lane.
    const __m128i mask = _mm_castps_si128(in);
    const __m128i rx = _mm_and_si128(_mm_cvttps_epi32(X), mask), ry = _mm_and_si128(_mm_cvttps_epi32(Y), mask);
    const __m128i index = _mm_madd_epi16(_mm_or_si128(ry, _mm_slli_epi32(rx, 16)), _mm_set1_epi32(width | (1 << 16)));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(at), index);
    return unsigned(_mm_movemask_ps(in));
#else
    float px[4], py[4];
    const unsigned ok = map4(x, y, d, px, py);
    unsigned inside = 0;
    for (int k = 0; k < 4; ++k) {
      int rx = 0, ry = 0;
      const bool in = ((ok >> k) & 1u) && pixel_in(width, height, vec2(px[k], py[k]), rx, ry);
      inside |= unsigned(in) << k;
      at[k] = in ? uint32_t(ry) * uint32_t(width) + uint32_t(rx) : 0u;
    }
    return inside;
#endif
  }

 private:
  // Rows of the 3×4 map from (x_c·d, y_c·d, d, 1), x_c = x + 0.5, to (X, Y, W) with
  // X/W, Y/W the pixel coordinates in `to` and W its depth.
  vec4 row_x_, row_y_, row_w_;

#ifdef PROXIMA_REPROJECT_SSE
  // map() in four lanes: X, Y = out_pixel; returns the lanes' w > 0 mask.
  // u = ((x + 0.5)·d, (y + 0.5)·d, d, 1); glm::dot(r, u) = (r.x·u.x + r.y·u.y) + (r.z·u.z + r.w).
  __m128 lanes(const int x[4], int y, const float d[4], __m128& X, __m128& Y) const {
    const __m128 dv = _mm_loadu_ps(d);
    const __m128 xc =
        _mm_add_ps(_mm_cvtepi32_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(x))), _mm_set1_ps(0.5f));
    const __m128 ux = _mm_mul_ps(xc, dv);
    const __m128 uy = _mm_mul_ps(_mm_set1_ps(float(y) + 0.5f), dv);
    const auto dot = [&](const vec4& r) {
      return _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(r.x), ux), _mm_mul_ps(_mm_set1_ps(r.y), uy)),
                        _mm_add_ps(_mm_mul_ps(_mm_set1_ps(r.z), dv), _mm_set1_ps(r.w)));
    };
    const __m128 w = dot(row_w_);
    X = _mm_div_ps(dot(row_x_), w);
    Y = _mm_div_ps(dot(row_y_), w);
    return _mm_cmpgt_ps(w, _mm_setzero_ps());
  }
#endif
};

}  // namespace proxima
