#include "proxima/viewer/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace proxima {

FlyCamera fly_camera_from(const Camera& camera, float speed) {
  FlyCamera fly;
  fly.position = camera.position;
  const vec3 f = camera_forward(camera);
  fly.yaw_deg = glm::degrees(std::atan2(f.x, -f.z));
  fly.pitch_deg = std::clamp(glm::degrees(std::asin(std::clamp(f.y, -1.0f, 1.0f))), -89.0f, 89.0f);
  fly.speed = std::clamp(speed, kMinFlySpeed, kMaxFlySpeed);
  fly.vfov_deg = camera.vfov_deg;
  fly.near = camera.near;
  fly.far = camera.far;
  return fly;
}

vec3 fly_forward(const FlyCamera& fly) {
  const float yaw = glm::radians(fly.yaw_deg), pitch = glm::radians(fly.pitch_deg);
  return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), -std::cos(pitch) * std::cos(yaw)};
}

bool update_fly_camera(FlyCamera& fly, const FlyInput& in, float dt_s) {
  bool changed = false;
  if (in.scroll != 0.0f)
    fly.speed = std::clamp(fly.speed * std::pow(1.25f, in.scroll), kMinFlySpeed, kMaxFlySpeed);
  if (in.mouse_px.x != 0.0f || in.mouse_px.y != 0.0f) {
    fly.yaw_deg = std::fmod(fly.yaw_deg + kMouseDegPerPx * in.mouse_px.x, 360.0f);
    fly.pitch_deg = std::clamp(fly.pitch_deg - kMouseDegPerPx * in.mouse_px.y, -89.0f, 89.0f);
    changed = true;
  }
  // Moves along the view direction flattened onto the floor plane, as in games: looking
  // down does not sink the camera.
  const float yaw = glm::radians(fly.yaw_deg);
  const vec3 ahead{std::sin(yaw), 0.0f, -std::cos(yaw)}, right{std::cos(yaw), 0.0f, std::sin(yaw)};
  vec3 move(0.0f);
  move += ahead * (float(in.forward) - float(in.back));
  move += right * (float(in.right) - float(in.left));
  move.y += float(in.up) - float(in.down);
  if (glm::length(move) > 0.0f && dt_s > 0.0f) {
    fly.position += glm::normalize(move) * fly.speed * dt_s;
    changed = true;
  }
  return changed;
}

Camera fly_to_camera(const FlyCamera& fly, int width, int height) {
  return look_at(fly.position, fly.position + fly_forward(fly), {0.0f, 1.0f, 0.0f}, fly.vfov_deg, width, height,
                 fly.near, fly.far);
}

}  // namespace proxima
