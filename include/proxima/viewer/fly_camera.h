// The viewer's fly camera: WASD moves in the view plane, Q/E (or Space/C) down
// and up, the mouse turns (yaw about world +Y, pitch clamped short of the poles), the
// scroll wheel scales the speed. Platform independent: front ends fill FlyInput.
#pragma once

#include "proxima/core/camera.h"

namespace proxima {

struct FlyCamera {
  vec3 position{0.0f};
  float yaw_deg = 0.0f;    // 0 looks down −Z, positive turns toward +X
  float pitch_deg = 0.0f;  // positive looks up; kept in [−89, 89]
  float speed = 1.0f;      // m/s
  float vfov_deg = 60.0f;
  float near = 0.01f, far = 1000.0f;
};

// What the user did during one frame.
struct FlyInput {
  bool forward = false, back = false, left = false, right = false, up = false, down = false;
  vec2 mouse_px{0.0f};  // mouse motion (x right, y down) while looking is on
  float scroll = 0.0f;  // wheel steps, + = faster
};

inline constexpr float kMouseDegPerPx = 0.2f;
inline constexpr float kMinFlySpeed = 0.05f, kMaxFlySpeed = 50.0f;

// The fly camera looking where `camera` looks (roll dropped), at `speed` m/s.
FlyCamera fly_camera_from(const Camera& camera, float speed);

// Applies one frame's input over `dt_s` seconds. Returns true if the view changed.
bool update_fly_camera(FlyCamera& fly, const FlyInput& input, float dt_s);

// Unit view direction.
vec3 fly_forward(const FlyCamera& fly);

// The pinhole camera of `fly` at width × height.
Camera fly_to_camera(const FlyCamera& fly, int width, int height);

}  // namespace proxima
