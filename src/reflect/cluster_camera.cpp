// Cluster camera construction.
// Paper: thesis ch. 4 §4.4 (聚类相机的构建, Figs. 24–25, Eq. 6). Symbols ↔ variables:
// P_c ↔ plane_point, n_c ↔ plane_normal, e ↔ input.eye, e0 ↔ mirrored_eye, e_c ↔ center,
// P_i ↔ input.points, Q_i ↔ input.ray_ends, aabb_n / aabb_f ↔ start_box / end_box,
// d_n / d_f ↔ their diagonals, f ↔ f, p ↔ input.pixel_footprint, w × h ↔ camera size.
// The thesis prints e_c = e0 + (P_c − e0)·f, which would put a planar cluster (f = 1) at P_c;
// its text requires e_c = e0 for f = 1 and a move towards P_c for 0 < f < 1 (which shrinks
// aabb_f faster than aabb_n until they match), so we use e_c = e0 + (P_c − e0)·(1 − f).
// The image plane is the window on the fitting plane; our Camera is a symmetric pinhole, so
// it looks at the window's centre and covers its four corners (an off-axis frustum would
// save the texels outside the window's trapezoid).
#include "proxima/reflect/cluster_camera.h"

#include <algorithm>
#include <cmath>

namespace proxima {

namespace {

constexpr float kMaxHalfFovDeg = 75.0f;

struct Box2 {
  vec2 min{kInf};
  vec2 max{-kInf};
  void extend(vec2 p) { min = glm::min(min, p); max = glm::max(max, p); }
  bool empty() const { return min.x > max.x; }
  float diagonal() const { return empty() ? 0.0f : glm::length(max - min); }
};

struct Plane {
  vec3 point, normal, tu, tv;

  // Central projection of x from `center` onto the plane, in plane coordinates (tu, tv);
  // false when x is not beyond the center as seen along the normal.
  bool project(vec3 center, vec3 x, vec2& out) const {
    float denom = glm::dot(x - center, normal);
    if (!(denom > 1e-12f)) return false;
    float s = glm::dot(point - center, normal) / denom;
    vec3 q = center + s * (x - center) - point;
    out = vec2(glm::dot(q, tu), glm::dot(q, tv));
    return true;
  }
};

// aabb of the projected start (points) and end points seen from `center`.
void project_boxes(const Plane& plane, vec3 center, const ClusterCameraInput& in, Box2& starts, Box2& ends) {
  vec2 q;
  for (vec3 p : in.points)
    if (plane.project(center, p, q)) starts.extend(q);
  for (vec3 p : in.ray_ends)
    if (plane.project(center, p, q)) ends.extend(q);
}

}  // namespace

std::optional<ClusterCamera> build_cluster_camera(const ClusterCameraInput& in) {
  if (in.points.empty() || in.points.size() != in.normals.size()) return std::nullopt;
  ClusterCamera out;

  // Step 1: fitting plane (mean point, mean normal), summed in double in a fixed order.
  dvec3 sum_p(0.0), sum_n(0.0);
  for (size_t i = 0; i < in.points.size(); ++i) {
    sum_p += dvec3(in.points[i]);
    sum_n += dvec3(in.normals[i]);
  }
  const double count = double(in.points.size());
  out.plane_point = vec3(sum_p / count);
  out.plane_normal = glm::length(sum_n) > 1e-12 ? vec3(glm::normalize(sum_n)) : in.normals[0];
  Plane plane{out.plane_point, out.plane_normal, vec3(0.0f), vec3(0.0f)};
  plane.tu = glm::normalize(std::abs(plane.normal.x) < 0.9f ? glm::cross(plane.normal, vec3(1, 0, 0))
                                                            : glm::cross(plane.normal, vec3(0, 1, 0)));
  plane.tv = glm::cross(plane.normal, plane.tu);

  bool same_normals = true;
  for (size_t i = 0; i < in.points.size(); ++i) {
    float dist = glm::dot(in.points[i] - plane.point, plane.normal);
    same_normals = same_normals && glm::dot(in.normals[i], plane.normal) >= 1.0f - 1e-6f;
    if (std::abs(dist) > in.plane_tolerance) same_normals = false;
  }
  out.planar = same_normals;
  out.clip_offset = 0.5f * in.plane_tolerance;
  if (!out.planar) {
    // A curved cluster's points lie on both sides of its fitting plane: the near plane goes
    // through the lowest of them, so no ray starts behind it (rays from the rim of a convex
    // cluster hit things between the rim and the fitting plane).
    for (vec3 p : in.points) out.clip_offset = std::min(out.clip_offset, glm::dot(p - plane.point, plane.normal) - in.plane_tolerance);
  }

  // Step 3a: mirrored eye.
  const float eye_dist = glm::dot(in.eye - plane.point, plane.normal);
  if (!(eye_dist > 0.0f)) return std::nullopt;
  out.mirrored_eye = in.eye - 2.0f * eye_dist * plane.normal;

  // Step 3b: f = d_n / d_f from the boxes seen from e0 (Eq. 6).
  Box2 start_box, end_box;
  project_boxes(plane, out.mirrored_eye, in, start_box, end_box);
  out.d_n = start_box.diagonal();
  out.d_f = end_box.diagonal();
  float f = 1.0f;
  if (!out.planar && out.d_f > 0.0f) f = std::clamp(out.d_n / out.d_f, 1e-3f, 1.0f);

  // Steps 3b–5 with the window check: a centre too close to the plane for its window
  // moves back towards e0.
  const float p = std::max(in.pixel_footprint, 1e-9f);
  const float max_tan = std::tan(glm::radians(kMaxHalfFovDeg));
  for (int attempt = 0;; ++attempt) {
    vec3 center = out.mirrored_eye + (plane.point - out.mirrored_eye) * (1.0f - f);
    // Step 4: image window = box of all projected start and end points, one footprint wider
    // on each side (each pixel covers a footprint; bilinear lookups need the margin).
    Box2 window, ends;
    project_boxes(plane, center, in, window, ends);
    if (!ends.empty()) {
      window.extend(ends.min);
      window.extend(ends.max);
    }
    if (window.empty()) return std::nullopt;
    window.min -= vec2(p);
    window.max += vec2(p);
    vec3 window_center = plane.point + 0.5f * (window.min.x + window.max.x) * plane.tu +
                         0.5f * (window.min.y + window.max.y) * plane.tv;
    vec3 axis = glm::normalize(window_center - center);
    vec3 up = std::abs(glm::dot(axis, plane.tv)) < 0.99f ? plane.tv : plane.tu;
    Camera cam = look_at(center, center + axis, up, 60.0f, 1, 1);
    float tan_x = 0.0f, tan_y = 0.0f, min_z = kInf;
    bool in_front = true;
    vec2 image_corner[4];  // window corners on the image plane at unit focal length, in order
    for (int k = 0; k < 4; ++k) {
      vec2 uv((k == 1 || k == 2) ? window.max.x : window.min.x, k >= 2 ? window.max.y : window.min.y);
      vec3 c = world_to_camera(cam, plane.point + uv.x * plane.tu + uv.y * plane.tv);
      float z = -c.z;
      if (!(z > 0.0f)) {
        in_front = false;
        break;
      }
      image_corner[k] = vec2(c.x, c.y) / z;
      tan_x = std::max(tan_x, std::abs(c.x) / z);
      tan_y = std::max(tan_y, std::abs(c.y) / z);
      min_z = std::min(min_z, z);
    }
    bool fits = in_front && tan_x <= max_tan && tan_y <= max_tan;
    if (!fits && f < 1.0f && attempt < 16) {
      f = std::min(1.0f, 2.0f * f);
      continue;
    }
    if (!in_front) {
      // Rays nearly parallel to the plane: keep the widest frustum allowed; rays outside
      // it fall back to the environment. Plane points inside it are at least the centre's
      // distance to the plane away, at under 80° to the axis.
      tan_x = tan_y = max_tan;
      for (int k = 0; k < 4; ++k) image_corner[k] = vec2((k == 1 || k == 2) ? max_tan : -max_tan, k >= 2 ? max_tan : -max_tan);
      min_z = 0.15f * glm::dot(plane.point - center, plane.normal);
    }
    tan_x = std::clamp(tan_x, 1e-6f, max_tan);
    tan_y = std::clamp(tan_y, 1e-6f, max_tan);

    // Step 5: the window's image (a quadrilateral) gets about (window area / p²)·scale²
    // texels, i.e. one texel per footprint p at scale 1; square pixels.
    const double pixels = double(in.points.size());
    double texels = double(in.resolution_scale) * double(in.resolution_scale) *
                    std::min(4.0 * pixels, double(window.max.x - window.min.x) *
                                               double(window.max.y - window.min.y) / (double(p) * double(p)));
    double quad_area = 0.0;  // shoelace, at unit focal length
    for (int k = 0; k < 4; ++k) {
      vec2 a = image_corner[k], b = image_corner[(k + 1) % 4];
      quad_area += 0.5 * (double(a.x) * double(b.y) - double(b.x) * double(a.y));
    }
    double focal = std::sqrt(texels / std::max(std::abs(quad_area), 1e-12));
    const double side = double(std::max(1, in.max_image_side));
    focal = std::min({focal, side / (2.0 * double(tan_x)), side / (2.0 * double(tan_y))});
    focal = std::max(focal, 0.5 / double(std::min(tan_x, tan_y)));  // at least one texel
    int width = std::clamp(int(std::ceil(2.0 * double(tan_x) * focal)), 1, int(side));
    int height = std::clamp(int(std::ceil(2.0 * double(tan_y) * focal)), 1, int(side));
    cam.width = width;
    cam.height = height;
    cam.vfov_deg = float(glm::degrees(2.0 * std::atan(double(height) / (2.0 * focal))));
    float far = 0.0f;
    for (vec3 q : in.ray_ends) far = std::max(far, -world_to_camera(cam, q).z);
    for (vec3 q : in.points) far = std::max(far, -world_to_camera(cam, q).z);
    cam.near = 0.5f * min_z;
    cam.far = std::max(1.01f * far, 2.0f * cam.near);
    out.camera = cam;
    out.f = f;
    return out;
  }
}

}  // namespace proxima
