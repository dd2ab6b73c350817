// `proxima view`: the interactive viewer (issue 12). Flags and checks here; the core is
// proxima/viewer/ (platform independent), the window apps/proxima/sdl/ (SDL2, optional).
#include <filesystem>
#include <iostream>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/load.h"
#include "proxima/viewer/camera_recording.h"
#include "view_window.h"

namespace proxima::cli {

namespace {

struct ViewFlags {
  CommonOptions common;
  CameraChoice camera;
  std::string technique = "reference";
  int move_scale = 0;
  std::string script;
  int frames = 0;
  std::string screenshot;
  std::string record;
  std::string play;
  bool no_overlay = false;
};

int run_view(const ViewFlags& f) {
  // Every flag checked, then the window availability, then the scene: nothing opens for bad input.
  if (f.common.width < 16 || f.common.width > 8192) fail_input("--width: must be in 16..8192");
  if (f.common.height < 16 || f.common.height > 8192) fail_input("--height: must be in 16..8192");
  if (f.common.threads < 0) fail_input("--threads: must be ≥ 0");
  if (f.move_scale < 0 || f.move_scale > 16) fail_input("--move-scale: must be in 0..16 (0 = adaptive)");
  if (f.frames < 0) fail_input("--frames: must be ≥ 0");
  if (!f.record.empty() && !is_builtin_scene(f.common.scene))
    fail_input("--record: needs a built-in --scene (the file names it as \"builtin\")");
  ViewWindowOptions wo;
  wo.script = parse_view_script(f.script);
  if (!view_window_available())
    fail_input("view: this proxima was built without SDL2 (install libsdl2-dev and rebuild)");

  ThreadLimit limit(f.common.threads);
  Scene scene = load_scene(f.common.scene);
  Scene played;
  if (!f.play.empty()) {
    played = load_scene(f.play);
    if (played.camera_paths.empty()) fail_input("--play: " + f.play + " has no camera path");
  }
  const Camera start = pick_camera(scene, f.camera, f.common.width, f.common.height);
  ViewerOptions vo;
  vo.move_scale = f.move_scale;
  vo.overlay = !f.no_overlay;
  vo.techniques.seed = f.common.seed;
  vo.speed = std::max(0.1f, 0.1f * scene_bounds(scene).diagonal());
  const std::string name = scene.name;
  ViewerSession session(std::move(scene), start, f.common.width, f.common.height, vo);
  int index = -1;
  for (size_t i = 0; i < session.techniques().size(); ++i)
    if (session.techniques()[i].name == f.technique) index = int(i);
  if (index < 0) {
    std::string names;
    for (const Technique& t : session.techniques()) names += (names.empty() ? "" : ", ") + t.name;
    fail_input("--technique: '" + f.technique + "' is not one of " + names);
  }
  if (!session.select_technique(index)) fail_input("--technique: " + session.status().message);

  wo.title = "proxima view - " + name;
  wo.scripted = !f.script.empty() || f.frames > 0 || !f.play.empty();
  wo.frames = f.frames;
  wo.screenshot = f.screenshot;
  wo.record = f.record;
  wo.record_scene = f.common.scene;
  if (!f.play.empty()) {
    // The recorded path of a --record file (its built-in scene may bring paths of its own).
    wo.play = &played.camera_paths.front();
    for (const CameraPath& p : played.camera_paths)
      if (p.name == kRecordedPathName) wo.play = &p;
  }
  const int code = run_view_window(session, wo);
  const ViewerStatus& st = session.status();
  std::cerr << "view: last frame " << st.render_width << "x" << st.render_height << " with "
            << session.techniques()[size_t(st.technique)].name << ", " << st.frame_ms << " ms\n";
  return code;
}

}  // namespace

Command register_view(CLI::App& root) {
  static ViewFlags f;
  auto* app = root.add_subcommand("view", "interactive viewer: fly through a scene and switch techniques live "
                                          "(SDL2 window; scripted with --script for tests)");
  add_scene_flag(app, f.common, "living-room");
  add_camera_flags(app, f.camera);
  f.common.width = 640;
  f.common.height = 360;
  add_size_flags(app, f.common);
  add_threads_flag(app, f.common);
  add_seed_flag(app, f.common);
  app->add_option("--technique", f.technique,
                  "initial technique: reference, envmap, rectified, cluster, temporal, shadows (keys 1-6)")
      ->capture_default_str();
  app->add_option("--move-scale", f.move_scale,
                  "while moving render at 1/N of the window per side (0 = adapt N to 15 frames/s)")
      ->capture_default_str();
  app->add_option("--script", f.script,
                  "scripted input, comma-separated: hold:KEY:N press:KEY mouse:DX:DY scroll:N resize:W:H idle:N "
                  "shot:FILE quit");
  app->add_option("--frames", f.frames, "stop after N frames (0 = when closed, or when --script/--play ends)")
      ->capture_default_str();
  app->add_option("--screenshot", f.screenshot, "PNG of the window's last frame");
  app->add_option("--record", f.record, "write the flown camera path as a scene file (use with --path recorded)");
  app->add_option("--play", f.play, "replay the camera path \"recorded\" of this scene file (a --record file), else its first");
  app->add_flag("--no-overlay", f.no_overlay, "start with the overlay hidden (H toggles it)");
  return {app, [] { return run_view(f); }};
}

}  // namespace proxima::cli
