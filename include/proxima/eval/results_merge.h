// The recorded runs of scripts/results.sh (proxima demo and the benchmarks it lacks) joined
// into the one results.json that docs/RESULTS.md is generated from (eval/results_page.h).
#pragma once

#include <string>
#include <vector>

#include "proxima/eval/results.h"

namespace proxima {

// One recorded run: its name (lower case, [a-z0-9_]) and its results.json.
struct NamedResults {
  std::string name;
  Results results;
};

// Joins runs into one Results: each run's metrics as "<name>_<metric>", its tables titled
// "<name>: <title>", its sections with ids "<name>-<id>" (table references renamed alike,
// image lists dropped: the images stay in the runs' own directories), and one section per
// run, id "<name>", holding the run's command line. `command` is the merged file's own
// command. Throws InputError when a name is malformed or repeated, when two metric names
// collide, or when the runs disagree on commit, build, CPU or threads (a page mixing
// binaries or machines would compare unlike figures).
Results merge_results(const std::vector<NamedResults>& runs, const std::vector<std::string>& command);

}  // namespace proxima
