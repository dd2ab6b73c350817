#include "proxima/eval/raster_agreement.h"

#include "proxima/raster/rasterizer.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima {

std::vector<CameraAgreement> raster_agreement_on_builtins(int size) {
  std::vector<CameraAgreement> out;
  for (const BuiltinSceneInfo& info : builtin_scenes()) {
    Scene scene = make_builtin_scene(info.name);
    RayScene rays(scene);
    for (const NamedCamera& nc : scene.cameras) {
      Camera cam = nc.camera;
      cam.width = cam.height = size;
      ImageU32 reference = trace_item_buffer(scene, rays, cam).triangle;
      ImageU32 raster = rasterize(scene, cam).triangle;
      out.push_back({info.name, nc.name, compare_id_buffers(scene, cam, raster, reference)});
    }
  }
  return out;
}

}  // namespace proxima
