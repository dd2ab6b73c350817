// A GIBR photograph item's photo.bin (sweep/gibr_photos.h), as the run's item reads it back
// from a sweep directory and merges it into a prepared model. Accepted bytes re-pack to the
// same bytes, and a mapping that unpacks merges into the model or fails with InputError.
#include "fuzz_util.h"
#include "proxima/gibr/gibr_model.h"
#include "proxima/scene/load.h"
#include "proxima/sweep/gibr_photos.h"

namespace {

// The seed's settings (scripts/fuzz_seeds.sh): rooms, one 32×24 photograph, both mappings.
const proxima::gibr::GibrModelOptions& options() {
  static const proxima::gibr::GibrModelOptions o = [] {
    proxima::gibr::GibrModelOptions m;
    m.photos = 1;
    m.photo_width = 32;
    m.photo_height = 24;
    m.supersample = 1;
    m.item_buffer = true;
    return m;
  }();
  return o;
}

const proxima::gibr::GibrModel& prepared() {
  static const proxima::gibr::GibrModel g = proxima::gibr::prepare_gibr_model(proxima::load_scene("rooms"), options());
  return g;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace proxima;
  fuzz::init_limits();
  const gibr::GibrModel& base = prepared();
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  fuzz::expect_input_errors_only([&] {
    gibr::PhotoMapping m = sweep::unpack_photo_mapping(bytes);
    FUZZ_CHECK(sweep::pack_photo_mapping(m) == bytes);
    gibr::GibrModel g;
    g.cameras = base.cameras;
    g.maps.grids = base.maps.grids;
    std::vector<gibr::PhotoMapping> photos;
    photos.push_back(std::move(m));
    gibr::add_photographs(g, std::move(photos), options());
    FUZZ_CHECK(g.maps.layers.size() == base.maps.grids.size());
  });
  return 0;
}
