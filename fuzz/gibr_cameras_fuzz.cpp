// GIBR camera files (gibr/photo_set.h, docs/gibr.md): every accepted photograph has a camera
// the renderers accept, lens fields in range, and small ones undistort without faults.
#include "fuzz_util.h"
#include "proxima/core/camera.h"
#include "proxima/gibr/photo_set.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace proxima;
  fuzz::init_limits();
  const auto path = fuzz::write_input(data, size, ".json");
  fuzz::expect_input_errors_only([&] {
    for (const gibr::CalibratedPhoto& p : gibr::read_camera_file(path)) {
      validate_camera(p.camera, "camera file photograph");  // an InputError here is a finding
      FUZZ_CHECK(std::abs(p.k1) <= 1.0 && std::abs(p.k2) <= 1.0);
      FUZZ_CHECK(std::isfinite(p.exposure) && p.exposure > 0.0);
      if (size_t(p.camera.width) * size_t(p.camera.height) <= 4096) {
        ImageU8 valid;
        const ImageF img(p.camera.width, p.camera.height, 3, 0.5f);
        const ImageF out = gibr::undistort_photo(img, p.camera, p.k1, p.k2, &valid);
        for (float v : out.data()) FUZZ_CHECK(std::isfinite(v));
      }
    }
  });
  return 0;
}
