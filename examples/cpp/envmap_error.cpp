// Uses the installed library (find_package(proxima)): renders the room-parallax scene with
// the Embree reference and with environment-map reflections (plain and position-rectified,
// Wang et al. 2012), then prints each one's error on the mirror's pixels. Exits 1 when
// rectification does not beat plain environment mapping there (its whole point).
#include <cstdio>
#include <vector>

#include "proxima/eval/image_error.h"
#include "proxima/reflect/distance_cube_map.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_select.h"
#include "proxima/trace/reference_renderer.h"

int main() {
  using namespace proxima;
  const Scene scene = make_builtin_scene("room-parallax");
  const RayScene rays(scene);  // Embree BVH
  const Camera camera = pick_camera(scene, {.camera = "left"}, 160, 120);
  const ImageF reference = render_reference(scene, rays, camera, {.max_bounces = 1});

  const std::vector<uint32_t> mirrors = reflective_objects(scene);
  const vec3 center = projection_center(scene, mirrors);
  const DistanceCubeMap map =
      render_distance_cube_map(scene, rays, center, {.resolution = 128, .exclude = mirrors});
  const ReflectorPixels pixels = rasterize_reflector_pixels(scene, camera, mirrors);
  ImageU8 mask(camera.width, camera.height, 1);
  for (size_t i = 0; i < mask.data().size(); ++i) mask.data()[i] = pixels.triangle.data()[i] != kNoTriangle;

  double mae[2] = {0, 0};
  for (EnvmapMethod method : {EnvmapMethod::Plain, EnvmapMethod::Rectified}) {
    const EnvmapInputs inputs{.method = method, .map = &map};
    const EnvmapFrame frame = shade_reflector_pixels(scene, rays, camera, pixels, inputs);
    const ImageError error = compare_images(frame.color, reference, &mask);
    mae[int(method)] = error.mae_avg;
    std::printf("%-9s mean error %.2f / 255 over %zu mirror pixels, PSNR %.1f dB\n", envmap_method_name(method),
                error.mae_avg, error.pixels, error.psnr_db);
  }
  return pixels.count > 0 && mae[1] < mae[0] ? 0 : 1;
}
