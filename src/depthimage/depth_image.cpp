// DepthImage (depth_image.h): conventional depth images on the rasterizer, and the
// pixel-to-pixel reprojection every redundancy test and metric uses.
#include "proxima/depthimage/depth_image.h"

#include <utility>

// SSE lanes give map()'s bits only if the scalar map() is not contracted into FMAs.
#if defined(__SSE2__) && !defined(__FMA__)
#define PROXIMA_MAP4_SSE 1
#include <emmintrin.h>
#endif

namespace proxima {

RasterOptions depth_image_raster_options(bool shade) {
  RasterOptions o;
  o.outputs = kRasterDepthId | (shade ? kRasterNormal | kRasterDiffuse : 0u);
  o.direct_light = shade;
  o.cull = CullMode::Back;
  return o;
}

DepthImage to_depth_image(const Camera& camera, RasterImages&& images) {
  DepthImage d;
  d.camera = camera;
  d.depth = std::move(images.depth);
  d.triangle = std::move(images.triangle);
  d.normal = std::move(images.normal);
  d.color = std::move(images.diffuse);
  return d;
}

DepthImage render_depth_image(const Scene& scene, const Camera& camera, bool shade) {
  RasterImages images;
  rasterize(scene, camera, depth_image_raster_options(shade), images, AcceptAllFragments{});
  return to_depth_image(camera, std::move(images));
}

size_t sample_count(const DepthImage& image) {
  size_t n = 0;
  for (uint32_t t : image.triangle.data()) n += t != kNoTriangle;
  return n;
}

vec3 sample_point(const DepthImage& image, int x, int y) {
  return unproject(image.camera, vec2(float(x) + 0.5f, float(y) + 0.5f), image.depth.at(x, y));
}

namespace {

// (x_c·d, y_c·d, d, 1) → world (homogeneous), for pixel center x_c, y_c at depth d.
glm::dmat4 pixel_depth_to_world(const Camera& c) {
  const double f = focal_length_px(c);
  // Camera space: x = (x_c − w/2)·d/f, y = (h/2 − y_c)·d/f, z = −d (camera.h unproject).
  glm::dmat4 to_cam(0.0);  // column-major: to_cam[col][row]
  to_cam[0][0] = 1.0 / f;
  to_cam[2][0] = -0.5 * c.width / f;
  to_cam[1][1] = -1.0 / f;
  to_cam[2][1] = 0.5 * c.height / f;
  to_cam[2][2] = -1.0;
  to_cam[3][3] = 1.0;
  return glm::inverse(glm::dmat4(view_matrix(c))) * to_cam;
}

// World → (X, Y, W, 1) with X/W, Y/W continuous pixel coordinates, W = −z_cam.
glm::dmat4 world_to_pixel_depth(const Camera& c) {
  const double f = focal_length_px(c);
  glm::dmat4 from_cam(0.0);
  from_cam[0][0] = f;
  from_cam[2][0] = -0.5 * c.width;
  from_cam[1][1] = -f;
  from_cam[2][1] = -0.5 * c.height;
  from_cam[2][2] = -1.0;
  from_cam[3][3] = 1.0;
  return from_cam * glm::dmat4(view_matrix(c));
}

}  // namespace

Reprojection::Reprojection(const Camera& from, const Camera& to) {
  const glm::dmat4 m = world_to_pixel_depth(to) * pixel_depth_to_world(from);
  auto row = [&](int r) { return vec4(float(m[0][r]), float(m[1][r]), float(m[2][r]), float(m[3][r])); };
  row_x_ = row(0);
  row_y_ = row(1);
  row_w_ = row(2);
}

unsigned Reprojection::map4(const int x[4], int y, const float d[4], float px[4], float py[4]) const {
#ifdef PROXIMA_MAP4_SSE
  // u = ((x + 0.5)·d, (y + 0.5)·d, d, 1); glm::dot(r, u) = (r.x·u.x + r.y·u.y) + (r.z·u.z + r.w).
  const __m128 dv = _mm_loadu_ps(d);
  const __m128 xc = _mm_add_ps(_mm_cvtepi32_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(x))), _mm_set1_ps(0.5f));
  const __m128 ux = _mm_mul_ps(xc, dv);
  const __m128 uy = _mm_mul_ps(_mm_set1_ps(float(y) + 0.5f), dv);
  const auto dot = [&](const vec4& r) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(r.x), ux), _mm_mul_ps(_mm_set1_ps(r.y), uy)),
                      _mm_add_ps(_mm_mul_ps(_mm_set1_ps(r.z), dv), _mm_set1_ps(r.w)));
  };
  const __m128 w = dot(row_w_);
  _mm_storeu_ps(px, _mm_div_ps(dot(row_x_), w));
  _mm_storeu_ps(py, _mm_div_ps(dot(row_y_), w));
  return unsigned(_mm_movemask_ps(_mm_cmpgt_ps(w, _mm_setzero_ps())));
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

}  // namespace proxima
