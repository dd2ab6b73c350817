// The setting of the soft-shadow experiment (thesis ch. 3, §3.3–3.4): a rectangular area
// light sized relative to the scene, its n×n point samples, the receivers (the output
// camera's visible points) and the pinhole cameras every light position renders from.
#pragma once

#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/scene/light.h"
#include "proxima/scene/scene.h"

namespace proxima {

// The thesis' light: its diagonal is `size` × the scene bounding-box diagonal (size 1 in
// Tables 8, 9, 11; 1/4 … 4 in Table 10). Ours is a horizontal square emitting downward
// (−y), centred on the scene's first point light (every sampling scene has one high above
// its geometry; without one: above the bounds' top by half the diagonal).
AreaLight shadow_light(const Scene& scene, float size);

// The point samples of an area light and the light itself. The light is one-sided, as the
// shading's area lights are: it reaches only points on the side its normal points to, so a
// receiver behind its plane is never lit by any sample (on_emitting_side), for every method.
struct LightSamples {
  AreaLight light;
  std::vector<vec3> points;
};

// n×n light samples at the centres of the light's n×n cells, row-major over (edge_v, edge_u).
LightSamples light_samples(const AreaLight& light, int n);

// p is strictly on the side `light` emits to (normal · (p − centre) > 0).
bool on_emitting_side(const AreaLight& light, vec3 p);

// Corners V_0 … V_3 of the light (Algorithm 5 step 1), in order around it.
std::vector<vec3> light_corners(const AreaLight& light);

// Visible surface points of the output image: position and shading normal (facing the
// camera) per pixel; mask = 1 where a surface is seen. Back faces culled, as the
// depth images do.
struct Receivers {
  Camera camera;
  ImageF position;  // 3 channels, world
  ImageF normal;    // 3 channels, unit
  ImageU8 mask;
  size_t count = 0;  // pixels with mask = 1
};
Receivers render_receivers(const Scene& scene, const Camera& camera);

// Camera placement shared by every light position (corners, centre, samples): all look at
// the centre of the region R = AABB(receivers ∪ light) ∩ scene bounds — which holds every
// occluder of a receiver–light segment — with one field of view that keeps R's eight
// corners inside the image from every light position given (plus 2 %, capped at 160°).
struct LightCameras {
  vec3 target{0.0f};
  vec3 up{0, 0, -1};
  float vfov_deg = 90.0f;
  float near = 0.01f, far = 1000.0f;
};
LightCameras fit_light_cameras(const Scene& scene, const AreaLight& light, const Receivers& receivers,
                               const std::vector<vec3>& eyes);

// Square camera at `eye` of the fitted placement.
Camera light_camera(const LightCameras& cams, vec3 eye, int resolution);

}  // namespace proxima
