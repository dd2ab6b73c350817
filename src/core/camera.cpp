#include "proxima/core/camera.h"

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "proxima/core/camera_projection.h"
#include "proxima/core/error.h"

namespace proxima {

Camera look_at(vec3 eye, vec3 target, vec3 up, float vfov_deg, int width, int height, float near,
               float far) {
  vec3 forward = glm::normalize(target - eye);
  vec3 right = glm::normalize(glm::cross(forward, up));
  vec3 true_up = glm::cross(right, forward);
  // Columns are the camera axes in world space: +X = right, +Y = up, +Z = −forward.
  mat3 basis(right, true_up, -forward);
  Camera cam;
  cam.position = eye;
  cam.orientation = glm::normalize(glm::quat_cast(basis));
  cam.vfov_deg = vfov_deg;
  cam.width = width;
  cam.height = height;
  cam.near = near;
  cam.far = far;
  return cam;
}

vec3 camera_forward(const Camera& cam) { return cam.orientation * vec3(0.0f, 0.0f, -1.0f); }
vec3 camera_right(const Camera& cam) { return cam.orientation * vec3(1.0f, 0.0f, 0.0f); }
vec3 camera_up(const Camera& cam) { return cam.orientation * vec3(0.0f, 1.0f, 0.0f); }

vec3 world_to_camera(const Camera& cam, vec3 world) {
  return glm::conjugate(cam.orientation) * (world - cam.position);
}

vec3 camera_to_world(const Camera& cam, vec3 cam_space) {
  return cam.orientation * cam_space + cam.position;
}

float focal_length_px(const Camera& cam) {
  return 0.5f * float(cam.height) / std::tan(glm::radians(cam.vfov_deg) * 0.5f);
}

std::optional<Projection> project(const Camera& cam, vec3 world) { return CameraProjection(cam)(world); }

vec3 unproject(const Camera& cam, vec2 pixel, float depth) { return CameraProjection(cam).unproject(pixel, depth); }

Ray ray_through(const Camera& cam, vec2 pixel) {
  float f = focal_length_px(cam);
  vec3 d((pixel.x - 0.5f * float(cam.width)) / f, (0.5f * float(cam.height) - pixel.y) / f, -1.0f);
  Ray ray;
  ray.origin = cam.position;
  ray.dir = glm::normalize(cam.orientation * d);
  return ray;
}

mat4 view_matrix(const Camera& cam) {
  mat4 rot = glm::mat4_cast(glm::conjugate(cam.orientation));
  return rot * glm::translate(mat4(1.0f), -cam.position);
}

mat4 projection_matrix(const Camera& cam) {
  return glm::perspective(glm::radians(cam.vfov_deg), float(cam.width) / float(cam.height), cam.near,
                          cam.far);
}

void validate_camera(const Camera& cam, const char* what) {
  std::string w(what);
  if (cam.width <= 0 || cam.height <= 0)
    fail_input(w + ": resolution " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
               " must be positive");
  if (cam.width > kMaxImageSide || cam.height > kMaxImageSide)
    fail_input(w + ": resolution " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
               " exceeds the maximum side " + std::to_string(kMaxImageSide));
  if (!std::isfinite(cam.vfov_deg) || cam.vfov_deg <= 0.0f || cam.vfov_deg >= 180.0f)
    fail_input(w + ": vertical field of view must be in (0, 180) degrees");
  if (!std::isfinite(cam.near) || !std::isfinite(cam.far) || cam.near <= 0.0f || cam.far <= cam.near)
    fail_input(w + ": clip distances need 0 < near < far");
  if (!is_finite(cam.position) || !std::isfinite(cam.orientation.w) || !std::isfinite(cam.orientation.x) ||
      !std::isfinite(cam.orientation.y) || !std::isfinite(cam.orientation.z))
    fail_input(w + ": camera position/orientation is not finite");
}

}  // namespace proxima
