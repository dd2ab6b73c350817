// The sweep manifest (docs/cli.md "proxima sweep"): study runs on scenes, each with options
// and optionally a grid of option values, expanded into work items — one study call each.
//
//   {"runs": [
//     {"study": "envmap_reflect", "scene": ["cornell", "room-reflector"],
//      "options": {"width": 96, "height": 72, "compare": true},
//      "grid": {"cube_size": [32, 64], "d_e": [0.01, 0.05]}},
//     {"study": "gibr", "scene": "rooms", "options": {"photos": 4}}
//   ]}
//
// A run expands scene by scene (in the order given), each over the grid's cartesian product
// (keys in name order, the last one varying fastest); a grid value overrides the same option
// of "options". Items are numbered in that order over all runs. A gibr run (without a camera
// file) becomes one item per photograph (its visibility map and radiance-map layers,
// gibr/gibr_model.h map_photograph) and the run's item, which merges them in photograph
// order and renders the novel views. A run with "frame_items": K (cluster_reflect, visibility:
// study/frame_split.h) becomes K frame-part items and the run's item, which merges them.
//
// `proxima demo` as a manifest: {"demo": {"full": true, "seed": 1, "width": 512, "height":
// 512, "only": ["gibr"]}} (every key optional, as `proxima demo`'s flags) expands into the
// demo's study runs (study/demo.h plan_demo), each run through the catalog from its
// reproducing command (its cluster and visibility runs split into kDemoFrameItems frame
// parts each); merge_sweep then writes the demo's report.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "proxima/study/catalog.h"
#include "proxima/study/demo.h"

namespace proxima::sweep {

struct SweepItem {
  // "i<number>_<study>" ([a-z0-9_], at most 32 characters): the item's directory under
  // DIR/items and the prefix of its metrics and tables in the merged results.
  std::string id;
  std::string scene;  // built-in name, or a file (relative to the manifest's directory)
  std::string study;  // a study_catalog() name
  study::OptionValues options;  // as given, over the study's defaults
  // ≥ 0: the per-photograph phases of photograph `photo` of this gibr run, stored as
  // photo.bin (sweep/gibr_photos.h); −1: the study call.
  int photo = -1;
  // A run split into frame parts (sweep/frame_parts.h): ≥ 0: part `frame_part` of
  // `frame_parts`, stored as part.bin; −1 with frame_parts > 1: the run's item, reading them.
  int frame_part = -1;
  int frame_parts = 1;
  // Items whose photo.bin or part.bin this one reads (a gibr run's photographs, a split run's
  // frame parts, in order).
  std::vector<size_t> inputs;

  // A photograph or a frame part: its bytes go into its run's item, which holds the results.
  bool is_part() const { return photo >= 0 || frame_part >= 0; }
};

// The frame parts of each cluster_reflect and visibility run of a demo manifest.
inline constexpr int kDemoFrameItems = 10;

struct Manifest {
  std::vector<SweepItem> items;
  std::optional<study::DemoOptions> demo;    // a demo manifest
  std::map<std::string, size_t> demo_items;  // its run directories → their items
};

// Parses and expands a manifest. A scene with '/' or '.' in it is a file; relative ones are
// taken relative to `base_dir`. Every study name and option is checked here (InputError
// naming `source`, the run and the option); scenes are loaded only when their item runs (a
// missing scene file fails that item, not the sweep).
Manifest parse_manifest(const std::string& json_text, const std::filesystem::path& base_dir,
                        const std::string& source);

// The demo manifest of `options` (full, seed, width, height, only) with its items listed
// under "items" (informative: a manifest whose items differ from its expansion by this
// binary is rejected as stale).
std::string demo_manifest_json(const study::DemoOptions& options);

// parse_manifest of a file; InputError naming the file when it cannot be read.
Manifest read_manifest(const std::filesystem::path& path);

}  // namespace proxima::sweep
