// Texture and environment images: read_image_linear (stb_image, PNG only).
#include "fuzz_util.h"
#include "proxima/core/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace proxima;
  fuzz::init_limits();
  const auto path = fuzz::write_input(data, size, ".png");
  fuzz::expect_input_errors_only([&] {
    const ImageF img = read_image_linear(path, 3);
    fuzz::check_image(img);
    FUZZ_CHECK(img.channels() == 3);
    for (float v : img.data()) FUZZ_CHECK(v >= 0.0f && v <= 1.0f);  // decoded 8-bit sRGB
  });
  return 0;
}
