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
// of "options". Items are numbered in that order over all runs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "proxima/study/catalog.h"

namespace proxima::sweep {

struct SweepItem {
  // "i<number>_<study>" ([a-z0-9_], at most 32 characters): the item's directory under
  // DIR/items and the prefix of its metrics and tables in the merged results.
  std::string id;
  std::string scene;  // built-in name, or a file (relative to the manifest's directory)
  std::string study;  // a study_catalog() name
  study::OptionValues options;  // as given, over the study's defaults
};

struct Manifest {
  std::vector<SweepItem> items;
};

// Parses and expands a manifest. A scene with '/' or '.' in it is a file; relative ones are
// taken relative to `base_dir`. Every study name and option is checked here (InputError
// naming `source`, the run and the option); scenes are loaded only when their item runs (a
// missing scene file fails that item, not the sweep).
Manifest parse_manifest(const std::string& json_text, const std::filesystem::path& base_dir,
                        const std::string& source);

// parse_manifest of a file; InputError naming the file when it cannot be read.
Manifest read_manifest(const std::filesystem::path& path);

}  // namespace proxima::sweep
