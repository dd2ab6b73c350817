// The measured-results page (docs/RESULTS.md), generated from the one results.json that
// scripts/results.sh records (eval/results_merge.h): per technique the error against
// the reference, the speed ratio against the reference and the paper's figure beside them,
// with the commands, machine, commit and threads.
//
// The page is a pure function of its input: no clock, no machine queries, fixed number
// formats, so regenerating it from the same results.json gives the same bytes.
#pragma once

#include <string>
#include <vector>

#include "proxima/eval/results.h"

namespace proxima {

struct ResultsPage {
  std::string markdown;
  // Metrics the page shows that the input lacks (printed as "—"); empty for a complete run.
  std::vector<std::string> missing;
};

// The page for a results.json written by merge_results from the runs of scripts/results.sh
// (run names demo, bench_trace, bench_raster, shadows, bench_view).
ResultsPage results_page(const Results& merged);

}  // namespace proxima
