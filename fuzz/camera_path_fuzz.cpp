// Camera paths (via scene files): every frame of every path must give a camera the
// renderers accept when the keys stay within the documented coordinate range.
#include "fuzz_util.h"
#include "proxima/core/camera.h"
#include "proxima/scene/load.h"

namespace {

bool moderate(const proxima::CameraPath& p) {
  auto ok = [](proxima::vec3 v) { return std::abs(v.x) <= 1e6f && std::abs(v.y) <= 1e6f && std::abs(v.z) <= 1e6f; };
  for (const proxima::CameraKey& k : p.keys)
    if (!ok(k.position) || !ok(k.target) || std::abs(k.time) > 1e6f) return false;
  return ok(p.up) && glm::length(p.up) >= 1e-3f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace proxima;
  fuzz::init_limits();
  const auto path = fuzz::write_input(data, size, ".json");
  fuzz::expect_input_errors_only([&] {
    const Scene scene = load_scene(path.string());
    fuzz::check_scene(scene);
    for (const CameraPath& p : scene.camera_paths) {
      // First, last and a few frames in between (paths may have a million frames).
      for (int f : {0, p.frames / 3, p.frames / 2, p.frames - 1}) {
        const float t = frame_time(p, f);
        const Camera cam = camera_at_time(p, t, 64, 48);
        if (moderate(p)) validate_camera(cam, "camera path frame");  // InputError = finding here
        (void)project(cam, scene.positions[0]);
      }
    }
    for (const NamedCamera& c : scene.cameras) validate_camera(c.camera, "scene camera");
  });
  return 0;
}
