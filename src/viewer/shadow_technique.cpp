// The viewer's soft-shadow technique, in its own file (only this entry needs shadows/).
#include "shadow_technique.h"

#include <optional>

#include "proxima/core/timer.h"
#include "proxima/shadows/light_setup.h"
#include "proxima/shadows/light_visibility.h"
#include "proxima/shadows/occluders.h"
#include "proxima/shadows/shadow_error.h"

namespace proxima {

// `proxima shadows` with NRR sampling: occluder meshes reconstructed once from depth images
// of the area light, shadow maps of them per frame. The light cameras are fitted to the
// whole scene (not one view's receivers) so the occluders stay valid as the camera flies.
Technique shadow_technique(std::shared_ptr<ViewerScene> vs, const TechniqueSettings& s) {
  struct Setup {
    AreaLight light;
    LightSamples samples;
    LightCameras cams;
    std::optional<Occluders> occluders;
  };
  auto setup = std::make_shared<Setup>();
  setup->light = shadow_light(vs->scene, s.shadow_light_size);
  setup->samples = light_samples(setup->light, s.shadow_light_samples);
  Receivers whole;  // the scene's bounding box as the receiver region
  const Bounds3 box = scene_bounds(vs->scene);
  whole.position = ImageF(2, 1, 3);
  whole.normal = ImageF(2, 1, 3);
  whole.mask = ImageU8(2, 1, 1, 1);
  whole.count = 2;
  for (int c = 0; c < 3; ++c) whole.position.at(0, 0, c) = box.min[c], whole.position.at(1, 0, c) = box.max[c];
  std::vector<vec3> eyes = setup->samples.points;
  for (const vec3& c : light_corners(setup->light)) eyes.push_back(c);
  setup->cams = fit_light_cameras(vs->scene, setup->light, whole, eyes);

  Technique t;
  t.name = "shadows";
  t.label = "soft shadows (NRR depth images)";
  t.whole_reference = true;
  t.render = [vs, s, setup](const Camera& camera) {
    TechniqueFrame out;
    if (!setup->occluders) {
      OccluderOptions occ;
      occ.resolution = s.occluder_resolution;
      setup->occluders = build_occluders(vs->scene, &vs->rays, setup->light, setup->cams, ShadowSampling::Nrr, occ);
      out.steps.push_back({"depth images (once)", setup->occluders->reference_ms});
      out.steps.push_back({"reconstruction (once)", setup->occluders->reconstruct_ms});
    }
    Stopwatch w;
    const Receivers receivers = render_receivers(vs->scene, camera);
    out.steps.push_back({"receivers", w.elapsed_ms()});
    ShadowMapOptions sm;
    sm.resolution = s.shadow_map_resolution;
    double ms = 0.0;
    const LightVisibility v = shadow_map_visibility(setup->occluders->scene, receivers, setup->samples, setup->cams, sm, &ms);
    out.steps.push_back({"shadow maps", ms});
    out.color = shadow_image(v, receivers);
    return out;
  };
  t.reference = [vs, setup](const Camera& camera, int, int) {
    const Receivers receivers = render_receivers(vs->scene, camera);
    return shadow_image(ray_visibility(vs->rays, vs->scene, receivers, setup->samples), receivers);
  };
  return t;
}

}  // namespace proxima
