// `proxima view`: the interactive viewer. Flags and checks here; the core is
// proxima/viewer/ (platform independent), the window apps/proxima/sdl/ (SDL2, optional).
#include <filesystem>
#include <iostream>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/load.h"
#include "proxima/viewer/camera_recording.h"
#include "view_flags.h"
#include "view_window.h"

namespace proxima::cli {

namespace {

struct ViewFlags {
  ViewSetup setup;
  std::string technique = "reference";
  std::string script;
  int frames = 0;
  std::string screenshot;
  std::string record;
  std::string play;
  bool no_overlay = false;
};

int run_view(const ViewFlags& f) {
  // Every flag checked, then the window availability, then the scene: nothing opens for bad input.
  const CommonOptions& common = f.setup.common;
  validate_view_flags(f.setup);
  require_at_least(f.frames, 0, "--frames");
  if (!f.record.empty() && !is_builtin_scene(common.scene))
    fail_input("--record: needs a built-in --scene (the file names it as \"builtin\")");
  ViewWindowOptions wo;
  wo.script = parse_view_script(f.script);
  if (!view_window_available())
    fail_input("view: this proxima was built without SDL2 (install libsdl2-dev and rebuild)");

  ThreadLimit limit(common.threads);
  ViewerOptions vo;
  vo.overlay = !f.no_overlay;
  const std::unique_ptr<ViewerSession> owned = make_view_session(f.setup, vo);
  ViewerSession& session = *owned;
  Scene played;
  if (!f.play.empty()) {
    played = load_scene(f.play);
    if (played.camera_paths.empty()) fail_input("--play: " + f.play + " has no camera path");
  }
  int index = -1;
  for (size_t i = 0; i < session.techniques().size(); ++i)
    if (session.techniques()[i].name == f.technique) index = int(i);
  if (index < 0) {
    std::string names;
    for (const Technique& t : session.techniques()) names += (names.empty() ? "" : ", ") + t.name;
    fail_input("--technique: '" + f.technique + "' is not one of " + names);
  }
  if (!session.select_technique(index)) fail_input("--technique: " + session.status().message);

  wo.title = "proxima view - " + session.scene().name;
  wo.scripted = !f.script.empty() || f.frames > 0 || !f.play.empty();
  wo.frames = f.frames;
  wo.screenshot = f.screenshot;
  wo.record = f.record;
  wo.record_scene = common.scene;
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
  add_view_flags(app, f.setup, "while moving render at 1/N of the window per side (0 = adapt N to 15 frames/s)");
  app->add_option("--technique", f.technique,
                  "initial technique: reference, envmap, rectified, cluster, temporal, shadows, gibr (keys 1-7)")
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
