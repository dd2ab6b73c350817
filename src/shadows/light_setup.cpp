// Soft-shadow setting (light_setup.h). Paper: Xie Naiwen, PhD thesis, ch. 3 §3.3–3.4
// (../shared/papers/004_d1af2812aec5f9c7.txt, lines 888–1000): rectangular light L whose
// diagonal is a multiple of the scene's bounding-box diagonal, 16×16 light samples s.
#include "proxima/shadows/light_setup.h"

#include <algorithm>
#include <cmath>

#include "proxima/core/parallel.h"
#include "proxima/depthimage/depth_image.h"

namespace proxima {

AreaLight shadow_light(const Scene& scene, float size) {
  const Bounds3 b = scene_bounds(scene);
  const float diagonal = b.diagonal();
  const vec3 center = scene.point_lights.empty() ? vec3(b.center().x, b.max.y + 0.5f * diagonal, b.center().z)
                                                 : scene.point_lights[0].position;
  const float side = size * diagonal / std::sqrt(2.0f);
  AreaLight light;
  light.edge_u = vec3(side, 0, 0);
  light.edge_v = vec3(0, 0, side);  // cross(x, z) = −y: emits downward
  light.corner = center - 0.5f * (light.edge_u + light.edge_v);
  return light;
}

LightSamples light_samples(const AreaLight& light, int n) {
  LightSamples s{light, {}};
  s.points.reserve(size_t(n) * size_t(n));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      s.points.push_back(light.point((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n)));
  return s;
}

bool on_emitting_side(const AreaLight& light, vec3 p) {
  return glm::dot(light.normal(), p - light.point(0.5f, 0.5f)) > 0.0f;
}

std::vector<vec3> light_corners(const AreaLight& light) {
  return {light.point(0, 0), light.point(1, 0), light.point(1, 1), light.point(0, 1)};
}

Receivers render_receivers(const Scene& scene, const Camera& camera) {
  RasterOptions o = depth_image_raster_options(false);
  o.outputs = kRasterDepthId | kRasterNormal;
  const RasterImages g = rasterize(scene, camera, o);
  Receivers r;
  r.camera = camera;
  r.position = ImageF(camera.width, camera.height, 3, 0.0f);
  r.normal = ImageF(camera.width, camera.height, 3, 0.0f);
  r.mask = ImageU8(camera.width, camera.height, 1, 0);
  parallel_for(size_t(camera.height), 16, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < camera.width; ++x) {
        if (g.triangle.at(x, y) == kNoTriangle) continue;
        const vec3 p = unproject(camera, vec2(float(x) + 0.5f, float(y) + 0.5f), g.depth.at(x, y));
        for (int k = 0; k < 3; ++k) {
          r.position.at(x, y, k) = p[k];
          r.normal.at(x, y, k) = g.normal.at(x, y, k);
        }
        r.mask.at(x, y) = 1;
      }
  });
  for (uint8_t m : r.mask.data()) r.count += m;
  return r;
}

LightCameras fit_light_cameras(const Scene& scene, const AreaLight& light, const Receivers& receivers,
                               const std::vector<vec3>& eyes) {
  Bounds3 region;
  for (int y = 0; y < receivers.mask.height(); ++y)
    for (int x = 0; x < receivers.mask.width(); ++x)
      if (receivers.mask.at(x, y))
        region.extend(vec3(receivers.position.at(x, y, 0), receivers.position.at(x, y, 1), receivers.position.at(x, y, 2)));
  for (const vec3& c : light_corners(light)) region.extend(c);
  const Bounds3 scene_box = scene_bounds(scene);
  region.min = glm::max(region.min, scene_box.min);
  region.max = glm::min(region.max, scene_box.max);
  if (!(region.min.x <= region.max.x && region.min.y <= region.max.y && region.min.z <= region.max.z))
    region = scene_box;

  LightCameras cams;
  cams.target = region.center();
  cams.up = glm::normalize(light.edge_v);
  constexpr float kMaxFov = 160.0f;
  const float max_tan = std::tan(0.5f * glm::radians(kMaxFov));
  float need = 0.0f, nearest = kInf, farthest = 0.0f;
  for (const vec3& eye : eyes) {
    const Camera probe = light_camera(cams, eye, 16);  // orientation only
    for (int k = 0; k < 8; ++k) {
      const vec3 corner = region.corner(k);
      const vec3 c = world_to_camera(probe, corner);
      const float depth = -c.z;
      farthest = std::max(farthest, glm::length(corner - eye));
      if (depth <= 1e-6f) {
        need = max_tan;
        continue;
      }
      nearest = std::min(nearest, depth);
      need = std::max(need, std::max(std::abs(c.x), std::abs(c.y)) / depth);
    }
  }
  cams.vfov_deg = std::min(kMaxFov, 2.0f * glm::degrees(std::atan(1.02f * std::min(need, max_tan))));
  const float diagonal = scene_box.diagonal();
  cams.near = std::max(1e-4f * diagonal, 0.5f * std::min(nearest, farthest));
  cams.far = 1.5f * farthest + 1e-3f * diagonal;
  return cams;
}

Camera light_camera(const LightCameras& cams, vec3 eye, int resolution) {
  const vec3 dir = glm::normalize(cams.target - eye);
  vec3 up = cams.up;
  if (std::abs(glm::dot(dir, up)) > 0.99f) up = glm::normalize(glm::cross(dir, vec3(1, 0, 0)));
  return look_at(eye, cams.target, up, cams.vfov_deg, resolution, resolution, cams.near, cams.far);
}

}  // namespace proxima
