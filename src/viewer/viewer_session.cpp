#include "proxima/viewer/viewer_session.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "proxima/core/image_io.h"
#include "proxima/core/timer.h"
#include "proxima/eval/image_error.h"
#include "proxima/viewer/bitmap_font.h"

namespace proxima {

namespace {

constexpr int kMinWindowSide = 16, kMaxWindowSide = 8192;

// The movement a held key drives (W A S D, E/space up, Q/C down); nullptr for other keys.
bool* movement_of(FlyInput& held, std::string_view key) {
  if (key == "w") return &held.forward;
  if (key == "s") return &held.back;
  if (key == "a") return &held.left;
  if (key == "d") return &held.right;
  if (key == "e" || key == "space") return &held.up;
  if (key == "q" || key == "c") return &held.down;
  return nullptr;
}

// Linear [0, 1] → sRGB 8-bit, 4096 steps (the display path runs once per window pixel).
const std::array<uint8_t, 4096>& srgb_table() {
  static const std::array<uint8_t, 4096> table = [] {
    std::array<uint8_t, 4096> t{};
    for (size_t i = 0; i < t.size(); ++i)
      t[i] = uint8_t(std::lround(255.0f * linear_to_srgb(float(i) / float(t.size() - 1))));
    return t;
  }();
  return table;
}

uint8_t to_srgb8(float linear) {
  const float v = std::isfinite(linear) ? std::clamp(linear, 0.0f, 1.0f) : 0.0f;
  return srgb_table()[size_t(v * 4095.0f + 0.5f)];
}

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

}  // namespace

ViewerSession::ViewerSession(Scene scene, const Camera& start, int window_width, int window_height,
                             const ViewerOptions& options)
    : scene_(std::make_shared<ViewerScene>(std::move(scene))),
      techniques_(make_techniques(scene_, options.techniques)),
      options_(options),
      fly_(fly_camera_from(start, options.speed)),
      width_(std::clamp(window_width, kMinWindowSide, kMaxWindowSide)),
      height_(std::clamp(window_height, kMinWindowSide, kMaxWindowSide)),
      move_scale_(options.move_scale > 0 ? options.move_scale : 2),
      window_(width_, height_, 4, 255) {}

ViewerSession::~ViewerSession() = default;

const Scene& ViewerSession::scene() const { return scene_->scene; }

Camera ViewerSession::camera() const { return fly_to_camera(fly_, width_, height_); }

void ViewerSession::key_down(std::string_view key) {
  status_.message.clear();
  if (bool* moving = movement_of(held_, key)) *moving = true;
  else if (key == "h") options_.overlay = !options_.overlay;
  else if (key == "-" || key == "=") {
    Technique& t = techniques_[size_t(status_.technique)];
    if (!t.adjust) {
      status_.message = t.label + ": no parameter";
    } else {
      status_.message = t.adjust(key == "=" ? 1 : -1);
      t.reset();
      invalidate();
    }
  }
  else if (key == "escape") quit_ = true;
  else if (key == "tab") {
    for (size_t k = 1; k <= techniques_.size(); ++k) {
      const int next = int((size_t(status_.technique) + k) % techniques_.size());
      if (techniques_[size_t(next)].unavailable.empty()) {
        select_technique(next);
        break;
      }
    }
  } else if (key.size() == 1 && key[0] >= '1' && key[0] <= '9')
    select_technique(key[0] - '1');
  // Anything else: ignored (bad keys must never crash the viewer).
}

void ViewerSession::key_up(std::string_view key) {
  if (bool* moving = movement_of(held_, key)) *moving = false;
}

void ViewerSession::mouse_motion(vec2 delta_px) {
  if (std::isfinite(delta_px.x) && std::isfinite(delta_px.y)) mouse_ += delta_px;
}

void ViewerSession::scroll(float steps) {
  if (std::isfinite(steps)) scroll_ += steps;
}

void ViewerSession::resize(int width, int height) {
  width = std::clamp(width, kMinWindowSide, kMaxWindowSide);
  height = std::clamp(height, kMinWindowSide, kMaxWindowSide);
  if (width == width_ && height == height_) return;
  width_ = width;
  height_ = height;
  window_ = ImageU8(width_, height_, 4, 255);
  techniques_[size_t(status_.technique)].reset();
  invalidate();
}

bool ViewerSession::select_technique(int index) {
  if (index < 0 || index >= int(techniques_.size())) {
    status_.message = "no technique on key " + std::to_string(index + 1);
    return false;
  }
  const Technique& t = techniques_[size_t(index)];
  if (!t.unavailable.empty()) {
    status_.message = t.label + ": " + t.unavailable;
    return false;
  }
  techniques_[size_t(status_.technique)].reset();
  status_.technique = index;
  t.reset();
  invalidate();
  return true;
}

void ViewerSession::set_camera(const Camera& camera) {
  fly_ = fly_camera_from(camera, fly_.speed);
  jumped_ = true;
}

void ViewerSession::invalidate() {
  status_.refined = false;
  status_.error_mae = -1.0;
  status_.reference_progress = 0.0;
  reference_rows_ = 0;
  reference_ = {};
  refined_ = {};
}

const ImageU8& ViewerSession::frame(float dt_s) {
  Stopwatch total;
  FlyInput input = held_;
  input.mouse_px = mouse_;
  input.scroll = scroll_;
  mouse_ = vec2(0.0f);
  scroll_ = 0.0f;
  const bool moved = update_fly_camera(fly_, input, std::clamp(dt_s, 0.0f, 0.5f)) || jumped_;
  jumped_ = false;
  if (moved) invalidate();
  status_.moving = moved;
  const Technique& t = techniques_[size_t(status_.technique)];

  if (moved || !status_.refined) {
    // Moving: 1/scale of the window per side; still: the full window, once.
    const int scale = moved ? move_scale_ : 1;
    const Camera camera = fly_to_camera(fly_, std::max(1, width_ / scale), std::max(1, height_ / scale));
    TechniqueFrame f = t.render(camera);
    status_.steps = std::move(f.steps);
    status_.note = std::move(f.note);
    status_.pending = f.pending;
    status_.scale = scale;
    status_.render_width = camera.width;
    status_.render_height = camera.height;
    present(f.color);
    if (f.pending) {
      // Nothing to refine or adapt to yet: the next frame renders again.
    } else if (!moved) {
      refined_ = std::move(f.color);
      status_.refined = true;
    } else if (options_.move_scale == 0) {
      // Keep moving frames within the budget: coarser when over, finer when the next finer
      // scale (cost ∝ pixels) is predicted to fit with a margin.
      const double ms = total.elapsed_ms();
      const int s = move_scale_;
      if (ms > options_.move_budget_ms && s < options_.max_move_scale) ++move_scale_;
      else if (s > 1 && ms * double(s * s) / double((s - 1) * (s - 1)) < 0.8 * options_.move_budget_ms) --move_scale_;
    }
  } else {
    if (reference_rows_ < height_) {
      // A band of the reference per frame, sized to ~reference_budget_ms.
      const Camera camera = fly_to_camera(fly_, width_, height_);
      const int rows = t.whole_reference ? height_ : std::min(band_rows_, height_ - reference_rows_);
      Stopwatch w;
      const ImageF part = t.reference(camera, reference_rows_, reference_rows_ + rows);
      const double ms = w.elapsed_ms();
      if (reference_.empty()) reference_ = ImageF(width_, height_, 3, 0.0f);
      for (int y = reference_rows_; y < reference_rows_ + rows; ++y)
        for (int x = 0; x < width_; ++x)
          for (int c = 0; c < 3; ++c) reference_.at(x, y, c) = part.at(x, y, c);
      reference_rows_ += rows;
      band_rows_ = std::clamp(int(double(rows) * options_.reference_budget_ms / std::max(ms, 1e-3)), 1, height_);
      status_.reference_progress = double(reference_rows_) / double(height_);
      if (reference_rows_ >= height_) status_.error_mae = compare_images(refined_, reference_).mae_avg;
    }
    present(refined_);
  }
  if (options_.overlay) draw_overlay();
  status_.frame_ms = total.elapsed_ms();
  return window_;
}

void ViewerSession::present(const ImageF& color) {
  // sRGB-encode the rendered frame once (it is up to scale² times smaller than the
  // window), then a nearest-neighbour upscale of whole 4-byte pixels.
  const int w = color.width(), h = color.height();
  std::vector<uint32_t> small(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t rgba[4] = {to_srgb8(color.at(x, y, 0)), to_srgb8(color.at(x, y, 1)), to_srgb8(color.at(x, y, 2)),
                               255};
      std::memcpy(&small[size_t(y) * size_t(w) + size_t(x)], rgba, 4);
    }
  std::vector<int> column(static_cast<size_t>(width_));
  for (int x = 0; x < width_; ++x) column[size_t(x)] = std::min(w - 1, int(int64_t(x) * w / width_));
  uint8_t* out = window_.data().data();
  for (int y = 0; y < height_; ++y) {
    const uint32_t* row = &small[size_t(std::min(h - 1, int(int64_t(y) * h / height_))) * size_t(w)];
    uint8_t* dst = out + size_t(y) * size_t(width_) * 4;
    for (int x = 0; x < width_; ++x) std::memcpy(dst + 4 * size_t(x), &row[column[size_t(x)]], 4);
  }
}

void ViewerSession::draw_overlay() {
  std::string panel;
  for (size_t i = 0; i < techniques_.size(); ++i) {
    const Technique& t = techniques_[i];
    panel += std::string(int(i) == status_.technique ? "> " : "  ") + t.key + " " + t.label +
             (t.unavailable.empty() ? "" : " (n/a)") + "\n";
  }
  // The whole-frame time is the previous frame's (this one is still being drawn).
  std::string info = format("last frame %.1f ms, ", status_.frame_ms) +
                     std::to_string(status_.render_width) + "x" + std::to_string(status_.render_height) +
                     (status_.moving ? " moving (1/" + std::to_string(status_.scale) + ")" : " still") + "\n";
  for (const StepTime& s : status_.steps) info += "  " + s.name + format(" %.1f ms", s.ms) + "\n";
  if (!status_.note.empty()) info += "  " + status_.note + "\n";
  if (status_.moving)
    info += "error: when the camera stops\n";
  else if (status_.error_mae >= 0.0)
    info += format("error vs reference: MAE %.2f /255\n", status_.error_mae);
  else
    info += format("reference %.0f%%\n", 100.0 * status_.reference_progress);
  info += format("speed %.2f m/s", fly_.speed);
  if (!status_.message.empty()) info += "\n" + status_.message;
  const std::string help = "WASD/QE move  mouse look  wheel speed  1-9/Tab technique  -/= parameter  H overlay  Esc";

  const int pad = 4;
  const int panel_h = text_height(panel) , info_h = text_height(info);
  const int box_w = std::max(text_width(panel), text_width(info)) + 2 * pad;
  shade_rect(window_, 0, 0, box_w, panel_h + info_h + 2 * pad);
  draw_text(window_, pad, pad, panel, {255, 255, 255, 255});
  // The current technique's line again in yellow.
  const int line = status_.technique;
  const std::string current = techniques_[size_t(line)].label;
  draw_text(window_, pad + 4 * kGlyphWidth, pad + line * kGlyphHeight, current, {255, 220, 0, 255});
  draw_text(window_, pad, pad + panel_h, info, {200, 230, 255, 255});
  const int hy = height_ - kGlyphHeight - pad;
  shade_rect(window_, 0, hy - pad, text_width(help) + 2 * pad, height_);
  draw_text(window_, pad, hy, help, {220, 220, 220, 255});
}

}  // namespace proxima
