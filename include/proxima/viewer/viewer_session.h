// The viewer's platform-independent core: input → fly camera → the current
// technique at a resolution that scales down while the camera moves and refines when it
// stops → the window's RGBA8 pixels with an overlay (technique panel, frame time per step,
// the error vs the reference once the camera has stopped and the reference — rendered a
// band of rows per frame — is complete). Front ends (the SDL window, the benchmark, tests)
// feed events and show `frame()`.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/scene/camera_path.h"
#include "proxima/viewer/fly_camera.h"
#include "proxima/viewer/techniques.h"

namespace proxima {

struct ViewerOptions {
  TechniqueSettings techniques;
  // While moving the frame is rendered at 1/scale of the window per side. 0 = adapt the
  // scale so frames stay within move_budget_ms; else this scale, fixed.
  int move_scale = 0;
  int max_move_scale = 8;
  double move_budget_ms = 1000.0 / 15.0;
  // Rows of the progressive reference per frame: adapted to ~reference_budget_ms per band.
  double reference_budget_ms = 100.0;
  float speed = 1.0f;  // initial fly speed, m/s
  bool overlay = true;
};

// What the last frame did (for the overlay, tests and the benchmark).
struct ViewerStatus {
  int technique = 0;             // index into techniques()
  int render_width = 0, render_height = 0;
  int scale = 1;
  bool moving = false;
  bool refined = false;          // a full-resolution frame of this view is on screen
  double reference_progress = 0.0;  // 0..1 rows of the reference done
  double error_mae = -1.0;       // MAE (0–255) vs the reference; < 0 until known
  double frame_ms = 0.0;         // the whole frame() call
  std::vector<StepTime> steps;   // of the technique's last render
  std::string note;              // its note (e.g. "building the GIBR model...")
  bool pending = false;          // its last frame was a placeholder (TechniqueFrame::pending)
  std::string message;           // e.g. why a key did nothing
};

class ViewerSession {
 public:
  // `scene` is loaded; `start` gives the initial view (its size is ignored).
  ViewerSession(Scene scene, const Camera& start, int window_width, int window_height, const ViewerOptions& options);
  ~ViewerSession();

  // Keys by name: "w" "a" "s" "d" "q" "e" (fly), "space" "c" (up/down), "1".."9" (technique),
  // "tab" (next technique), "-" / "=" (the technique's parameter), "h" (overlay on/off), "escape" (quit). Unknown names are ignored.
  void key_down(std::string_view key);
  void key_up(std::string_view key);
  void mouse_motion(vec2 delta_px);
  void scroll(float steps);
  void resize(int width, int height);  // clamped to [16, 8192]
  bool select_technique(int index);    // false (and a message) if unavailable
  void set_camera(const Camera& camera);  // jumps there (playback); counts as a move

  // Renders one frame after `dt_s` seconds of input. The image is window-sized RGBA8.
  const ImageU8& frame(float dt_s);

  bool quit_requested() const { return quit_; }
  const ViewerStatus& status() const { return status_; }
  const std::vector<Technique>& techniques() const { return techniques_; }
  const FlyCamera& fly() const { return fly_; }
  Camera camera() const;  // at window size
  const Scene& scene() const;

 private:
  void invalidate();
  void present(const ImageF& color);
  void draw_overlay();

  std::shared_ptr<ViewerScene> scene_;
  std::vector<Technique> techniques_;
  ViewerOptions options_;
  FlyCamera fly_;
  FlyInput held_;
  vec2 mouse_{0.0f};
  float scroll_ = 0.0f;
  bool jumped_ = false;
  int width_, height_;
  int move_scale_;
  bool quit_ = false;
  ViewerStatus status_;
  ImageF refined_;          // full-resolution frame of the current view
  ImageF reference_;        // progressive reference of the current view
  int reference_rows_ = 0;  // rows done
  int band_rows_ = 8;
  ImageU8 window_;
};

}  // namespace proxima
