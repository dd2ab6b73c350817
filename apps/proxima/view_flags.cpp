#include "view_flags.h"

#include <algorithm>

#include "proxima/core/error.h"
#include "proxima/core/range_check.h"
#include "proxima/scene/load.h"

namespace proxima::cli {

void add_view_flags(CLI::App* app, ViewSetup& s, const char* move_scale_help) {
  s.common.width = 640;
  s.common.height = 360;
  add_common_flags(app, s.common, {.scene = "living-room", .camera = &s.camera, .out = false});
  app->add_option("--move-scale", s.move_scale, move_scale_help)->capture_default_str();
}

void validate_view_flags(const ViewSetup& s) {
  require_in_range(s.common.width, 16, 8192, "--width");
  require_in_range(s.common.height, 16, 8192, "--height");
  require_at_least(s.common.threads, 0, "--threads");
  require_in_range(s.move_scale, 0, 16, "--move-scale", "(0 = adaptive)");
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
