// Six-face cube camera: the projection behind cube environment and distance maps.
// Faces are ordered +X, −X, +Y, −Y, +Z, −Z; each face is a square 90° pinhole camera at
// `center`. Distance maps store Euclidean distance to `center` (DESIGN.md).
#pragma once

#include <array>

#include "proxima/core/camera.h"

namespace proxima {

struct CubeCamera {
  vec3 center{0.0f};
  int resolution = 512;  // pixels per face side
  float near = 0.01f;
  float far = 1000.0f;
};

enum class CubeFace : int { PosX = 0, NegX = 1, PosY = 2, NegY = 3, PosZ = 4, NegZ = 5 };

// The pinhole camera of one face (90° fov, square, looking along the face's axis).
Camera face_camera(const CubeCamera& cube, int face);
std::array<Camera, 6> face_cameras(const CubeCamera& cube);

struct CubeTexel {
  int face;    // 0..5
  vec2 pixel;  // continuous pixel coordinates within that face's camera image
};

// The face a direction (need not be unit) falls on, and where, consistent with face_camera():
// project(face_camera(cube, f), center + dir) gives the same pixel.
CubeTexel cube_lookup(const CubeCamera& cube, vec3 dir);

}  // namespace proxima
