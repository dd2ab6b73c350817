// A built-in 5×7 bitmap font (printable ASCII) for the viewer's overlay: no font files,
// no dependency, the same pixels on every machine (the screenshot tests compare them).
#pragma once

#include <cstdint>
#include <string_view>

#include "proxima/core/image.h"

namespace proxima {

inline constexpr int kGlyphWidth = 6;   // 5 columns + 1 spacing, before scaling
inline constexpr int kGlyphHeight = 9;  // 7 rows + descender + 1 spacing

struct Rgba8 {
  uint8_t r = 255, g = 255, b = 255, a = 255;
};

// Draws `text` with its top-left corner at (x, y) into a 4-channel RGBA8 image, each font
// pixel as a scale × scale block; clipped to the image. Characters outside 32..126 draw as
// '?'; '\n' starts a new line. Returns the width drawn in pixels (longest line).
int draw_text(ImageU8& rgba, int x, int y, std::string_view text, Rgba8 color, int scale = 1);

// Width and height `text` would take at `scale`.
int text_width(std::string_view text, int scale = 1);
int text_height(std::string_view text, int scale = 1);

// Darkens the rectangle [x0, x1) × [y0, y1) (clipped) so text on it stays readable.
void shade_rect(ImageU8& rgba, int x0, int y0, int x1, int y1, float keep = 0.35f);

}  // namespace proxima
