// Float images: read_exr (tinyexr, compiled into the fuzz build so it is instrumented).
#include "fuzz_util.h"
#include "proxima/core/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace proxima;
  fuzz::init_limits();
  const auto path = fuzz::write_input(data, size, ".exr");
  fuzz::expect_input_errors_only([&] { fuzz::check_image(read_exr(path)); });
  return 0;
}
