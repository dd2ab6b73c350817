// DepthImage (depth_image.h): conventional depth images on the rasterizer, and the
// pixel-to-pixel reprojection every redundancy test and metric uses.
#include "proxima/depthimage/depth_image.h"

#include <utility>

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

}  // namespace proxima
