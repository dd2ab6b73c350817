// Flags and set-up shared by `proxima view` and `proxima bench view`: the scene, start
// view, window size (640×360), threads, seed and --move-scale, and the session built from them.
#pragma once

#include <memory>

#include "command.h"
#include "proxima/viewer/viewer_session.h"

namespace proxima::cli {

struct ViewSetup {
  CommonOptions common;
  CameraChoice camera;
  int move_scale = 0;  // 0 = adaptive
};

void add_view_flags(CLI::App* app, ViewSetup& setup, const char* move_scale_help);

// InputError naming the flag for a bad size, thread count or move scale.
void validate_view_flags(const ViewSetup& setup);

// Loads the scene and builds the session at the start view (fly speed: a tenth of the
// scene diagonal per second).
std::unique_ptr<ViewerSession> make_view_session(const ViewSetup& setup, ViewerOptions options);

}  // namespace proxima::cli
