#include "proxima/eval/image_error.h"

#include <cmath>

#include <gtest/gtest.h>

#include "proxima/core/image_io.h"

namespace proxima {
namespace {

TEST(ImageError, IdenticalImagesHaveZeroErrorAndInfinitePsnr) {
  ImageF a(8, 4, 3, 0.3f);
  ImageError e = compare_images(a, a);
  EXPECT_EQ(e.pixels, 32u);
  EXPECT_EQ(e.mae_avg, 0.0);
  EXPECT_TRUE(std::isinf(e.psnr_db));
}

TEST(ImageError, MeasuresOnTheDisplayedScale) {
  ImageF ref(4, 4, 3, 0.0f), approx(4, 4, 3, 0.0f);
  approx.at(1, 1, 0) = 1.0f;  // one red value from black to white: 255 on one pixel
  ImageError e = compare_images(approx, ref);
  EXPECT_NEAR(e.mae[0], 255.0 / 16.0, 1e-3);  // float sRGB encoding
  EXPECT_EQ(e.mae[1], 0.0);
  EXPECT_NEAR(e.max_abs[0], 255.0, 1e-3);  // float sRGB encoding
  EXPECT_NEAR(e.mae_avg, 255.0 / 48.0, 1e-3);  // float sRGB encoding
  // Mid grey: linear 0.5 shows as sRGB 188 of 255.
  ImageF grey(1, 1, 3, 0.5f), black(1, 1, 3, 0.0f);
  EXPECT_NEAR(compare_images(grey, black).mae[1], 255.0 * linear_to_srgb(0.5f), 1e-3);
}

TEST(ImageError, MaskSelectsPixels) {
  ImageF ref(2, 1, 3, 0.0f), approx(2, 1, 3, 0.0f);
  approx.at(0, 0, 2) = 1.0f;
  ImageU8 mask(2, 1, 1, 0);
  mask.at(1, 0) = 1;
  EXPECT_EQ(compare_images(approx, ref, &mask).mae[2], 0.0);
  mask.at(0, 0) = 1;
  EXPECT_NEAR(compare_images(approx, ref, &mask).mae[2], 127.5, 1e-3);  // float sRGB encoding
  ImageF err = error_image(approx, ref);
  EXPECT_NEAR(err.at(0, 0), 85.0, 1e-4);
  EXPECT_EQ(err.at(1, 0), 0.0f);
}

TEST(ImageError, HeatmapRampIsMonotoneInBrightnessAndSaturates) {
  ImageF err(5, 1, 1);
  for (int x = 0; x < 5; ++x) err.at(x, 0) = float(x) * 10.0f;  // 0..40, max 30
  ImageF h = error_heatmap(err, 30.0f);
  auto lum = [&](int x) { return h.at(x, 0, 0) + h.at(x, 0, 1) + h.at(x, 0, 2); };
  for (int x = 1; x < 4; ++x) EXPECT_GT(lum(x), lum(x - 1));
  EXPECT_EQ(lum(4), lum(3));  // saturated
}

}  // namespace
}  // namespace proxima
