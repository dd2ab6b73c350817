// Pinhole camera: placement, projection and rays.
// Conventions (DESIGN.md): camera space looks down −Z, +X right, +Y up. Pixel (x, y) covers
// [x, x+1) × [y, y+1) with row 0 at the top; continuous pixel coordinates put the center of
// pixel (x, y) at (x + 0.5, y + 0.5). Depth is the positive view-space distance −z_cam.
#pragma once

#include <optional>

#include "proxima/core/math.h"

namespace proxima {

struct Camera {
  vec3 position{0.0f};
  quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // camera → world rotation
  float vfov_deg = 60.0f;                    // full vertical field of view
  int width = 512;
  int height = 512;
  float near = 0.01f;  // clip distances along −z_cam, meters
  float far = 1000.0f;
};

// Camera at `eye` looking at `target`; `up` need not be orthogonal to the view direction
// but must not be parallel to it.
Camera look_at(vec3 eye, vec3 target, vec3 up, float vfov_deg, int width, int height,
               float near = 0.01f, float far = 1000.0f);

vec3 camera_forward(const Camera& cam);  // unit world direction of −Z_cam
vec3 camera_right(const Camera& cam);    // unit world direction of +X_cam
vec3 camera_up(const Camera& cam);       // unit world direction of +Y_cam

vec3 world_to_camera(const Camera& cam, vec3 world);
vec3 camera_to_world(const Camera& cam, vec3 cam_space);

// Focal length in pixels: (height / 2) / tan(vfov / 2). Pixels are square.
float focal_length_px(const Camera& cam);

struct Projection {
  vec2 pixel;   // continuous pixel coordinates (centers at +0.5)
  float depth;  // −z_cam, > 0
};

// World point → pixel coordinates and depth; nullopt when the point is not in front of
// the camera (depth ≤ 0). The pixel may lie outside the image.
std::optional<Projection> project(const Camera& cam, vec3 world);

// Continuous pixel coordinates + depth (−z_cam) → world point. Inverse of project().
vec3 unproject(const Camera& cam, vec2 pixel, float depth);

// Ray from the camera center through continuous pixel coordinates; unit direction,
// tmin = 0, tmax = +inf. t along it is Euclidean distance, not depth.
Ray ray_through(const Camera& cam, vec2 pixel);

// OpenGL-style matrices (right-handed, clip z in [−w, w]) for rasterizers and harnesses.
mat4 view_matrix(const Camera& cam);
mat4 projection_matrix(const Camera& cam);

// Rejects cameras that cannot render (non-positive or huge resolution, fov outside
// (0, 180), near ≤ 0 or far ≤ near, non-finite values): throws InputError naming `what`.
void validate_camera(const Camera& cam, const char* what);

// Largest width or height proxima accepts for any image.
inline constexpr int kMaxImageSide = 16384;

}  // namespace proxima
