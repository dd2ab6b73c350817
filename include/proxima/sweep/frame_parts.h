// A study run split into frame parts as sweep items (study/frame_split.h): each part is an
// item of its own, stored as part.bin — its frame figures, its image roles and the files it
// wrote; the run's item reads every part's part.bin, reduces the figures concatenated in
// part order to the run's metrics and tables and writes the parts' files beside them, so its
// results do not depend on which process ran which part.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "proxima/eval/results.h"
#include "proxima/scene/scene.h"
#include "proxima/study/catalog.h"
#include "proxima/study/frame_split.h"
#include "proxima/sweep/item.h"

namespace proxima::sweep {

// One part as bytes: its figures, its results' image roles and its files.
struct FramePartData {
  study::FrameFigures figures;
  std::map<std::string, std::string> images;  // role → file
  ItemFiles files;
};

std::string pack_frame_part(const FramePartData& part);
// Throws std::runtime_error on malformed bytes.
FramePartData unpack_frame_part(std::string_view bytes);

// The run's results from its parts' part.bin (in part order): the study's results from the
// figures concatenated (study_part_results), the image roles of every part, and every
// part's files written into `out`.
Results run_with_frame_parts(const Scene& scene, const std::string& study, const study::OptionValues& options,
                             const study::StudyOutput& out, const std::vector<std::string>& parts);

}  // namespace proxima::sweep
