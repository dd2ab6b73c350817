// Soft-shadow errors of thesis ch. 3 §3.4.2, per receiver pixel, scaled to 0..255 (the
// thesis' 16×16 = 256 samples make the scale a count):
//   visibility error = 255 · #{samples whose visibility is wrong} / n²
//   intensity error  = 255 · |#lit(approx) − #lit(truth)| / n²
// so visibility error ≥ intensity error (wrong "lit" and wrong "dark" cancel in the
// intensity). Means are over receiver pixels (pixels with no surface have no shadow).
#pragma once

#include "proxima/core/image.h"
#include "proxima/shadows/light_setup.h"
#include "proxima/shadows/light_visibility.h"

namespace proxima {

struct ShadowError {
  double intensity_mean = 0.0, intensity_max = 0.0;
  double visibility_mean = 0.0, visibility_max = 0.0;
  ImageF image;  // 3 channels: green = too bright, red = too dark, ×4 intensity error / 255
};

ShadowError compare_visibility(const LightVisibility& approx, const LightVisibility& truth, const Receivers& receivers);

// Lit fraction as grey (receivers), background dark blue.
ImageF shadow_image(const LightVisibility& v, const Receivers& receivers);

}  // namespace proxima
