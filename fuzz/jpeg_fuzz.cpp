// JPEG textures: read_image_linear's libjpeg-turbo path (the input starts with FF D8 FF).
// libturbojpeg is the system's shared library, not instrumented: the fuzzer steers by
// proxima's own branches and ASan sees only proxima's memory accesses and the allocator,
// so this target checks the wrapper (header limits, buffer sizes, warnings as errors, CMYK
// conversion) more than libjpeg-turbo itself, which OSS-Fuzz covers.
#include "fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  proxima::fuzz::read_8bit_image(data, size, ".jpg");
  return 0;
}
