// Radial lens distortion of a pinhole camera's image (Brown's model: OpenCV's first two
// coefficients; docs/gibr.md): the lens puts the pinhole image's normalized point
// (x, y) = ((px − cx)/f, (py − cy)/f) at (x, y)·(1 + k1 r² + k2 r⁴), r² = x² + y² (principal
// point at the image center, f the camera's focal length in pixels).
#pragma once

#include "proxima/core/camera.h"
#include "proxima/core/math.h"

namespace proxima::gibr {

struct Lens {
  double k1 = 0.0, k2 = 0.0;
  bool pinhole() const { return k1 == 0.0 && k2 == 0.0; }
};

// Where the lens puts the pinhole image point `p` (pixel coordinates of `camera`).
glm::dvec2 distort_pixel(const Camera& camera, const Lens& lens, glm::dvec2 p);
// The pinhole image point the lens puts at `q` (fixed-point iteration; the distortion must be
// monotonic out to q's radius, as read_camera_file checks out to the image corners).
glm::dvec2 undistort_pixel(const Camera& camera, const Lens& lens, glm::dvec2 q);
// A radius (pinhole pixels) that holds the undistorted image of the disk of `radius` pixels
// around the lens image point q: radius × the largest stretch of the inverse distortion
// (1 / the least eigenvalue of the distortion's Jacobian) over that disk (sampled at 9 radii),
// with a margin of the stretch's variation across those samples.
double undistorted_radius(const Camera& camera, const Lens& lens, glm::dvec2 q, double radius);

}  // namespace proxima::gibr
