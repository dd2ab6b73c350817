// A gibr run as sweep items: each photograph's per-photograph phases (its visibility map and
// radiance-map layers, gibr/gibr_model.h map_photograph) is an item of its own, stored as the
// bytes of its PhotoMapping (photo.bin); the run's item reads them all and merges them in
// photograph order (add_photographs), so its results do not depend on which process mapped
// which photograph.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "proxima/eval/results.h"
#include "proxima/gibr/gibr_model.h"
#include "proxima/scene/scene.h"
#include "proxima/study/catalog.h"
#include "proxima/study/study.h"

namespace proxima::sweep {

// The mapping as bytes and back; unpack throws std::runtime_error on malformed bytes.
std::string pack_photo_mapping(const gibr::PhotoMapping& mapping);
gibr::PhotoMapping unpack_photo_mapping(std::string_view bytes);

// Photograph `photo` of the gibr run with `options` on `scene`, packed; empty when the path
// gave fewer photograph poses than asked for. The photograph's own image is kept only when
// the run writes photo_images.
std::string run_gibr_photo(const Scene& scene, const study::OptionValues& options, int photo);

// The gibr study (run_gibr) with every photograph's mapping taken from `photos` (packed, in
// photograph order; empty ones skipped) instead of computed.
Results run_gibr_with_photos(const Scene& scene, const study::OptionValues& options, const study::StudyOutput& out,
                             const std::vector<std::string>& photos);

}  // namespace proxima::sweep
