// A frame part's part.bin (sweep/frame_parts.h), as a split run's item reads it back from a
// sweep directory and reduces its figures with the study's own code. Accepted bytes re-pack
// to bytes that read back the same; any figures reduce to results or fail with an exception the sweep
// reports as the item's error — never a crash or a read out of bounds.
#include <stdexcept>

#include "fuzz_util.h"
#include "proxima/scene/load.h"
#include "proxima/study/catalog.h"
#include "proxima/sweep/frame_parts.h"
#include "proxima/sweep/manifest.h"

namespace {

// The seed's runs (scripts/fuzz_seeds.sh): a cluster and a visibility run in two parts each.
constexpr const char* kManifest = R"({"runs": [
  {"study": "cluster_reflect", "scene": "room-reflector", "frame_items": 2,
   "options": {"width": 32, "height": 24, "path": "0", "frames": 3, "ss": 1, "cube_size": 16, "compare": true}},
  {"study": "visibility", "scene": "rooms", "frame_items": 2,
   "options": {"width": 32, "height": 24, "frames": 3, "selfcheck_rays": 50}}]})";

struct Run {
  const proxima::sweep::SweepItem* item;
  proxima::Scene scene;
};

const std::vector<Run>& runs() {
  static const proxima::sweep::Manifest manifest = proxima::sweep::parse_manifest(kManifest, ".", "part_bin");
  static const std::vector<Run> r = [] {
    std::vector<Run> out;
    for (const proxima::sweep::SweepItem& item : manifest.items)
      if (!item.is_part()) out.push_back({&item, proxima::load_scene(item.scene)});
    return out;
  }();
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace proxima;
  const std::vector<Run>& reducers = runs();
  fuzz::init_limits();
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  sweep::FramePartData part;
  try {
    part = sweep::unpack_frame_part(bytes);
  } catch (const std::runtime_error&) {
    return 0;
  }
  const std::string packed = sweep::pack_frame_part(part);
  FUZZ_CHECK(sweep::pack_frame_part(sweep::unpack_frame_part(packed)) == packed);
  for (const Run& run : reducers) {
    try {
      const Results r = study::study_part_results(run.item->study, run.scene, run.item->options, part.figures);
      (void)r;
    } catch (const std::exception&) {
    }
  }
  return 0;
}
