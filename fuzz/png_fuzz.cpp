// PNG textures and environment images: read_image_linear through stb_image.
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  proxima::fuzz::read_8bit_image(data, size, ".png");
  return 0;
}
