#include "proxima/scene/light.h"

#include <algorithm>

#include "proxima/core/cube_camera.h"

namespace proxima {

vec3 environment_radiance(const Environment& env, vec3 dir) {
  if (!env.has_cube_map()) return env.color;
  CubeCamera cube;
  cube.resolution = env.cube[0].width();
  CubeTexel t = cube_lookup(cube, dir);
  const ImageF& face = env.cube[size_t(t.face)];
  int x = std::clamp(int(t.pixel.x), 0, face.width() - 1);
  int y = std::clamp(int(t.pixel.y), 0, face.height() - 1);
  return vec3(face.at(x, y, 0), face.at(x, y, 1), face.at(x, y, 2));
}

}  // namespace proxima
