// JPEG textures: read_image_linear's libjpeg-turbo path (the input starts with FF D8 FF).
// libturbojpeg is the system's shared library, not instrumented: the fuzzer steers by
// proxima's own branches and ASan sees only proxima's memory accesses and the allocator,
// so this target checks the wrapper (header limits, buffer sizes, warnings as errors, CMYK
// conversion) more than libjpeg-turbo itself, which OSS-Fuzz covers.
#include "fuzz_util.h"
#include "proxima/core/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace proxima;
  fuzz::init_limits();
  const auto path = fuzz::write_input(data, size, ".jpg");
  fuzz::expect_input_errors_only([&] {
    const ImageF img = read_image_linear(path, 3);
    fuzz::check_image(img);
    FUZZ_CHECK(img.channels() == 3);
    for (float v : img.data()) FUZZ_CHECK(v >= 0.0f && v <= 1.0f);  // decoded 8-bit sRGB
  });
  return 0;
}
