// Scripted input for the viewer (`proxima view --script`): tests and demos drive it
// headlessly with the same events a user makes. Comma-separated tokens, one frame each
// unless said otherwise:
//   hold:KEY:N     KEY held for N frames (e.g. hold:w:10 flies forward)
//   press:KEY      KEY pressed and released (e.g. press:3 switches to technique 3)
//   mouse:DX:DY    mouse motion in pixels
//   scroll:N       N wheel steps
//   resize:W:H     the window resized
//   idle:N         N frames without input (the view refines, the reference progresses)
//   shot:FILE      screenshot (PNG) after the previous token's frame; no frame of its own
//   quit           closes the window (the SDL front end: an SDL_QUIT event, as the close button)
#pragma once

#include <string>
#include <vector>

#include "proxima/core/math.h"

namespace proxima {

class ViewerSession;

struct ViewEvent {
  enum class Type { KeyDown, KeyUp, Mouse, Scroll, Resize, Quit } type;
  std::string key;
  vec2 value{0.0f};  // mouse delta, scroll steps (x) or window size
};

struct ScriptFrame {
  std::vector<ViewEvent> before;    // applied before the frame renders
  std::vector<ViewEvent> after;     // after it (key releases of a hold)
  std::vector<std::string> shots;   // screenshots of this frame
};

// Throws InputError naming `flag` and the bad token.
std::vector<ScriptFrame> parse_view_script(const std::string& text, const char* flag = "--script");

// Applies one event to a session.
void apply_event(ViewerSession& session, const ViewEvent& event);

}  // namespace proxima
