// Wavefront OBJ (+ MTL references resolved beside it) through load_scene: assimp import, node flattening, material mapping, limits, sanitize.
#include "fuzz_util.h"
#include "proxima/scene/load.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace proxima;
  fuzz::init_limits();
  const auto path = fuzz::write_input(data, size, ".obj");
  fuzz::expect_input_errors_only([&] { fuzz::check_scene(load_scene(path.string())); });
  return 0;
}
