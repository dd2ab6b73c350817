#include "proxima/eval/image_error.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "proxima/core/image_io.h"
#include "proxima/core/math.h"

namespace proxima {
namespace {

double display_value(float linear) {
  float v = std::isfinite(linear) ? std::clamp(linear, 0.0f, 1.0f) : 0.0f;
  return 255.0 * double(linear_to_srgb(v));
}

bool selected(const ImageU8* mask, int x, int y) { return !mask || mask->at(x, y) != 0; }

// Inferno-like ramp, control points sampled from matplotlib's inferno (sRGB).
vec3 inferno(float t) {
  static const vec3 kStops[] = {{0.001f, 0.000f, 0.014f}, {0.258f, 0.039f, 0.406f}, {0.578f, 0.148f, 0.404f},
                                {0.865f, 0.317f, 0.226f}, {0.988f, 0.645f, 0.040f}, {0.988f, 0.998f, 0.645f}};
  constexpr int n = int(std::size(kStops)) - 1;
  t = std::clamp(t, 0.0f, 1.0f) * float(n);
  int i = std::min(int(t), n - 1);
  vec3 srgb = glm::mix(kStops[i], kStops[i + 1], t - float(i));
  return vec3(srgb_to_linear(srgb.x), srgb_to_linear(srgb.y), srgb_to_linear(srgb.z));
}

}  // namespace

ImageError compare_images(const ImageF& approx, const ImageF& reference, const ImageU8* mask) {
  assert(approx.width() == reference.width() && approx.height() == reference.height());
  assert(approx.channels() >= 3 && reference.channels() >= 3);
  ImageError e;
  double sum[3] = {0, 0, 0}, sq = 0.0;
  for (int y = 0; y < approx.height(); ++y)
    for (int x = 0; x < approx.width(); ++x) {
      if (!selected(mask, x, y)) continue;
      ++e.pixels;
      for (int c = 0; c < 3; ++c) {
        double d = std::fabs(display_value(approx.at(x, y, c)) - display_value(reference.at(x, y, c)));
        sum[c] += d;
        sq += d * d;
        e.max_abs[c] = std::max(e.max_abs[c], d);
      }
    }
  if (e.pixels == 0) return e;
  for (int c = 0; c < 3; ++c) e.mae[c] = sum[c] / double(e.pixels);
  e.mae_avg = (e.mae[0] + e.mae[1] + e.mae[2]) / 3.0;
  double mse = sq / (3.0 * double(e.pixels));
  e.psnr_db = mse > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : std::numeric_limits<double>::infinity();
  return e;
}

ImageF error_image(const ImageF& approx, const ImageF& reference, const ImageU8* mask) {
  ImageF err(approx.width(), approx.height(), 1, 0.0f);
  for (int y = 0; y < approx.height(); ++y)
    for (int x = 0; x < approx.width(); ++x) {
      if (!selected(mask, x, y)) continue;
      double d = 0.0;
      for (int c = 0; c < 3; ++c)
        d += std::fabs(display_value(approx.at(x, y, c)) - display_value(reference.at(x, y, c)));
      err.at(x, y) = float(d / 3.0);
    }
  return err;
}

ImageF error_heatmap(const ImageF& error, float max_error, const ImageU8* mask) {
  ImageF out(error.width(), error.height(), 3);
  float scale = max_error > 0.0f ? 1.0f / max_error : 0.0f;
  for (int y = 0; y < error.height(); ++y)
    for (int x = 0; x < error.width(); ++x) {
      vec3 c = selected(mask, x, y) ? inferno(error.at(x, y) * scale) : vec3(0.2f);
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = c[k];
    }
  return out;
}

ImageF heatmap_legend(int width, int height) {
  ImageF out(width, height, 3);
  for (int x = 0; x < width; ++x) {
    vec3 c = inferno(width > 1 ? float(x) / float(width - 1) : 0.0f);
    for (int y = 0; y < height; ++y)
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = c[k];
  }
  return out;
}

}  // namespace proxima
