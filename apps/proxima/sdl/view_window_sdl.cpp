// SDL2 front end of `proxima view`: a resizable window with a software surface (no GPU
// needed, runs under Xvfb). Everything but events and pixels is in ViewerSession.
#include <SDL.h>

#include <cstdio>
#include <memory>
#include <string>

#include "../view_window.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/viewer/camera_recording.h"

namespace proxima::cli {

namespace {

// SDL key → the session's key names; "" for keys the viewer does not use.
std::string key_name(SDL_Keycode k) {
  if (k >= SDLK_a && k <= SDLK_z) return std::string(1, char('a' + (k - SDLK_a)));
  if (k >= SDLK_1 && k <= SDLK_9) return std::string(1, char('1' + (k - SDLK_1)));
  switch (k) {
    case SDLK_SPACE: return "space";
    case SDLK_MINUS:
    case SDLK_KP_MINUS: return "-";
    case SDLK_EQUALS:
    case SDLK_PLUS:
    case SDLK_KP_PLUS: return "=";
    case SDLK_TAB: return "tab";
    case SDLK_ESCAPE: return "escape";
    default: return "";
  }
}

// The pixels the window shows, read back from its surface.
void screenshot(SDL_Window* window, const std::string& file) {
  SDL_Surface* surface = SDL_GetWindowSurface(window);
  if (!surface) fail_input("screenshot " + file + ": " + SDL_GetError());
  std::unique_ptr<SDL_Surface, decltype(&SDL_FreeSurface)> rgba(
      SDL_ConvertSurfaceFormat(surface, SDL_PIXELFORMAT_RGBA32, 0), SDL_FreeSurface);
  if (!rgba) fail_input("screenshot " + file + ": " + SDL_GetError());
  ImageU8 image(rgba->w, rgba->h, 3);
  SDL_LockSurface(rgba.get());
  for (int y = 0; y < rgba->h; ++y) {
    const auto* row = static_cast<const uint8_t*>(rgba->pixels) + size_t(y) * size_t(rgba->pitch);
    for (int x = 0; x < rgba->w; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = row[4 * x + c];
  }
  SDL_UnlockSurface(rgba.get());
  write_png(file, image);
}

void show(SDL_Window* window, const ImageU8& frame) {
  SDL_Surface* target = SDL_GetWindowSurface(window);  // re-fetched: a resize replaces it
  if (!target) return;
  SDL_Surface* source = SDL_CreateRGBSurfaceWithFormatFrom(const_cast<uint8_t*>(frame.data().data()), frame.width(),
                                                           frame.height(), 32, 4 * frame.width(), SDL_PIXELFORMAT_RGBA32);
  if (!source) return;
  if (source->w == target->w && source->h == target->h)
    SDL_BlitSurface(source, nullptr, target, nullptr);
  else
    SDL_BlitScaled(source, nullptr, target, nullptr);  // until the session has seen the resize
  SDL_FreeSurface(source);
  SDL_UpdateWindowSurface(window);
}

// The pending window events: keys, mouse (left button held turns the camera), resize, close.
void handle_input(ViewerSession& session, bool& looking) {
  SDL_Event e;
  while (SDL_PollEvent(&e)) {
    switch (e.type) {
      case SDL_QUIT: session.key_down("escape"); break;
      case SDL_WINDOWEVENT:
        if (e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED) session.resize(e.window.data1, e.window.data2);
        break;
      case SDL_KEYDOWN:
        if (!e.key.repeat) session.key_down(key_name(e.key.keysym.sym));
        break;
      case SDL_KEYUP: session.key_up(key_name(e.key.keysym.sym)); break;
      case SDL_MOUSEBUTTONDOWN: looking = looking || e.button.button == SDL_BUTTON_LEFT; break;
      case SDL_MOUSEBUTTONUP: looking = looking && e.button.button != SDL_BUTTON_LEFT; break;
      case SDL_MOUSEMOTION:
        if (looking) session.mouse_motion(vec2(float(e.motion.xrel), float(e.motion.yrel)));
        break;
      case SDL_MOUSEWHEEL: session.scroll(float(e.wheel.y)); break;
      default: break;
    }
  }
}

// A script frame's events before the frame renders; resize and close go through the window.
void apply_script_before(SDL_Window* window, ViewerSession& session, const ScriptFrame& step) {
  for (const ViewEvent& ev : step.before) {
    if (ev.type == ViewEvent::Type::Resize) SDL_SetWindowSize(window, int(ev.value.x), int(ev.value.y));
    if (ev.type == ViewEvent::Type::Quit) {
      // The window manager's close button: an SDL_QUIT the event loop handles next.
      SDL_Event q{};
      q.type = SDL_QUIT;
      SDL_PushEvent(&q);
      continue;
    }
    apply_event(session, ev);
  }
}

}  // namespace

bool view_window_available() { return true; }

int run_view_window(ViewerSession& session, const ViewWindowOptions& o) {
  // The frames are CPU images blitted to the window surface: no GL renderer behind the
  // surface, so no Mesa (llvmpipe) threads still alive at exit, where LeakSanitizer's exit
  // check stops every thread and now and then crashes on one.
  SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
  if (SDL_Init(SDL_INIT_VIDEO) != 0)
    fail_input(std::string("view: cannot open a window (no display? try xvfb-run): ") + SDL_GetError());
  // No SDL_Quit(): it unloads the X11 libraries SDL dlopen()ed, after which LeakSanitizer
  // cannot attribute their process-lifetime allocations (fuzz/lsan.supp names those
  // libraries) and reports them as leaks of an unknown module. The process exits next.
  const Camera start = session.camera();
  std::unique_ptr<SDL_Window, decltype(&SDL_DestroyWindow)> window(
      SDL_CreateWindow(o.title.c_str(), SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, start.width, start.height,
                       SDL_WINDOW_RESIZABLE),
      SDL_DestroyWindow);
  if (!window) fail_input(std::string("view: cannot open a window: ") + SDL_GetError());

  CameraRecorder recorder;
  bool looking = false;  // left mouse button held: mouse motion turns the camera
  uint64_t last = SDL_GetPerformanceCounter();
  const double tick = 1.0 / double(SDL_GetPerformanceFrequency());
  const bool ends = !o.script.empty() || o.play != nullptr || o.frames > 0;
  size_t script_frames = o.script.size();
  if (o.play) script_frames = std::max(script_frames, size_t(o.play->frames));
  size_t frame = 0;
  std::string last_message;
  for (;; ++frame) {
    handle_input(session, looking);
    if (session.quit_requested()) break;
    if (o.frames > 0 && frame >= size_t(o.frames)) break;
    if (ends && o.frames == 0 && frame >= script_frames) break;
    const ScriptFrame* step = frame < o.script.size() ? &o.script[frame] : nullptr;
    if (step) apply_script_before(window.get(), session, *step);
    if (o.play && frame < size_t(o.play->frames)) {
      const Camera c = camera_at_time(*o.play, frame_time(*o.play, int(frame)), start.width, start.height);
      session.set_camera(c);
    }
    if (session.quit_requested()) break;
    const uint64_t now = SDL_GetPerformanceCounter();
    const float dt = o.scripted ? 1.0f / 30.0f : float(double(now - last) * tick);
    last = now;
    show(window.get(), session.frame(dt));
    if (!o.record.empty()) record_camera(recorder, session.fly(), dt, session.status().moving);
    if (step) {
      for (const std::string& file : step->shots) screenshot(window.get(), file);
      for (const ViewEvent& ev : step->after) apply_event(session, ev);
    }
    if (session.quit_requested()) break;
    // Messages (e.g. why a key did nothing) also on the terminal, once each.
    const ViewerStatus& st = session.status();
    if (st.message != last_message && !st.message.empty()) std::fprintf(stderr, "view: %s\n", st.message.c_str());
    last_message = st.message;
    // Nothing left to refine: wait for input instead of spinning.
    if (!ends && !st.moving && st.refined && st.error_mae >= 0.0) SDL_WaitEventTimeout(nullptr, 50);
  }
  std::fprintf(stderr, "view: %zu frames\n", frame);
  if (!o.screenshot.empty()) screenshot(window.get(), o.screenshot);
  if (!o.record.empty()) write_recorded_path(o.record, o.record_scene, recorder);
  return 0;
}

}  // namespace proxima::cli
