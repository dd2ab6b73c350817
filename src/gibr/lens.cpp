#include "proxima/gibr/lens.h"

#include <algorithm>
#include <cmath>

namespace proxima::gibr {

namespace {

double radial(const Lens& l, double r2) { return 1.0 + l.k1 * r2 + l.k2 * r2 * r2; }

// The least eigenvalue of the distortion's Jacobian at normalized radius² r2: tangential
// 1 + k1 r² + k2 r⁴, radial d/dr [r (1 + k1 r² + k2 r⁴)] = 1 + 3 k1 r² + 5 k2 r⁴.
double least_stretch(const Lens& l, double r2) {
  return std::min(radial(l, r2), 1.0 + 3.0 * l.k1 * r2 + 5.0 * l.k2 * r2 * r2);
}

}  // namespace

glm::dvec2 distort_pixel(const Camera& camera, const Lens& lens, glm::dvec2 p) {
  const double f = focal_length_px(camera), cx = 0.5 * camera.width, cy = 0.5 * camera.height;
  const double x = (p.x - cx) / f, y = (p.y - cy) / f, s = radial(lens, x * x + y * y);
  return {cx + f * x * s, cy + f * y * s};
}

glm::dvec2 undistort_pixel(const Camera& camera, const Lens& lens, glm::dvec2 q) {
  const double f = focal_length_px(camera), cx = 0.5 * camera.width, cy = 0.5 * camera.height;
  const double xd = (q.x - cx) / f, yd = (q.y - cy) / f;
  double x = xd, y = yd;
  for (int it = 0; it < 50; ++it) {
    const double s = radial(lens, x * x + y * y);
    x = xd / s;
    y = yd / s;
  }
  return {cx + f * x, cy + f * y};
}

double undistorted_radius(const Camera& camera, const Lens& lens, glm::dvec2 q, double radius) {
  if (lens.pinhole()) return radius;
  const double f = focal_length_px(camera), cx = 0.5 * camera.width, cy = 0.5 * camera.height;
  const glm::dvec2 u = undistort_pixel(camera, lens, q);
  const double r = std::hypot(u.x - cx, u.y - cy) / f;
  // The disk maps within about radius / least stretch of u: test the stretch across it.
  const double reach = 2.0 * radius / (f * std::max(1e-3, least_stretch(lens, r * r)));
  double least = INFINITY, most = 0.0;
  for (int k = -4; k <= 4; ++k) {
    const double rr = std::max(0.0, r + reach * k / 4.0);
    least = std::min(least, least_stretch(lens, rr * rr));
    most = std::max(most, least_stretch(lens, rr * rr));
  }
  // Between the samples the stretch varies by less than across all of them.
  least = std::max(1e-3, least);
  return radius / least * (1.0 + (most - least) / least + 1e-9);
}

}  // namespace proxima::gibr
