#include "view_flags.h"

#include <algorithm>

#include "proxima/core/error.h"
#include "proxima/scene/load.h"

namespace proxima::cli {

void add_view_flags(CLI::App* app, ViewSetup& s, const char* move_scale_help) {
  add_scene_flag(app, s.common, "living-room");
  add_camera_flags(app, s.camera);
  s.common.width = 640;
  s.common.height = 360;
  add_size_flags(app, s.common);
  add_threads_flag(app, s.common);
  add_seed_flag(app, s.common);
  app->add_option("--move-scale", s.move_scale, move_scale_help)->capture_default_str();
}

void validate_view_flags(const ViewSetup& s) {
  if (s.common.width < 16 || s.common.width > 8192) fail_input("--width: must be in 16..8192");
  if (s.common.height < 16 || s.common.height > 8192) fail_input("--height: must be in 16..8192");
  if (s.common.threads < 0) fail_input("--threads: must be ≥ 0");
  if (s.move_scale < 0 || s.move_scale > 16) fail_input("--move-scale: must be in 0..16 (0 = adaptive)");
}

std::unique_ptr<ViewerSession> make_view_session(const ViewSetup& s, ViewerOptions o) {
  Scene scene = load_scene(s.common.scene);
  const Camera start = pick_camera(scene, s.camera, s.common.width, s.common.height);
  o.move_scale = s.move_scale;
  o.techniques.seed = s.common.seed;
  o.speed = std::max(0.1f, 0.1f * scene_bounds(scene).diagonal());
  return std::make_unique<ViewerSession>(std::move(scene), start, s.common.width, s.common.height, o);
}

}  // namespace proxima::cli
