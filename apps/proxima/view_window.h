// The window front end of `proxima view` (apps/proxima/sdl/view_window_sdl.cpp, built only
// when CMake finds SDL2): events in, ViewerSession frames out. cmd_view.cpp owns the flags.
#pragma once

#include <string>
#include <vector>

#include "proxima/scene/camera_path.h"
#include "proxima/viewer/view_script.h"
#include "proxima/viewer/viewer_session.h"

namespace proxima::cli {

struct ViewWindowOptions {
  std::string title;
  std::vector<ScriptFrame> script;  // scripted input; non-empty: the run ends with it
  bool scripted = false;            // fixed 1/30 s frame steps (script, --frames, --play)
  int frames = 0;                   // stop after this many frames (0 = no limit)
  std::string screenshot;           // PNG of the last frame
  std::string record;               // camera path file written at exit (empty = none)
  std::string record_scene;         // its "builtin"
  const CameraPath* play = nullptr; // replayed one frame per path frame, then the run ends
};

// True when this binary has a window front end.
bool view_window_available();

// Runs until the window closes, Esc, or the script / --frames / --play ends. Returns the
// exit code; throws InputError when no window can be opened (no display).
int run_view_window(ViewerSession& session, const ViewWindowOptions& options);

}  // namespace proxima::cli
