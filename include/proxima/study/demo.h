// The demo: every technique on the built-in scenes beside its reference, as one Results with a
// section per technique (prose, tables, images, plots and the commands that reproduce each
// figure). `proxima demo` publishes it as results.json and renders index.html from that file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "proxima/core/progress.h"
#include "proxima/eval/results.h"

namespace proxima::study {

struct DemoOptions {
  bool full = false;              // the papers' settings (hours) instead of the ≤ 10-minute ones
  std::vector<std::string> only;  // ids of the sections to run (demo_section_ids); empty = all
  int threads = 0;                // worker threads, 0 = all cores; shown in every reproducing command
  uint64_t seed = 1;              // seed of every sampled quantity
  int width = 512, height = 512;  // reference renders, pixels
  std::string out_arg;            // the output directory as the reproducing commands spell it
};

// Section ids in page order.
std::vector<std::string> demo_section_ids();

// Throws InputError naming --only or --threads.
void validate(const DemoOptions& options);

struct DemoRun {
  Results results;
  int failed_sections = 0;  // sections that threw; each is reported on the page
};

// One study run of the demo: the subdirectory of the report it writes into and the
// `proxima` command reproducing it (without "proxima", --out and --threads). The command is
// the run's one description: a sweep runs it through the study catalog
// (study::catalog_run_from_command), so the demo's settings are written only in its sections.
struct DemoStudyRun {
  std::string dir;
  std::vector<std::string> args;
};

// Every study run run_demo(options) makes, in order, without running any: the sections run
// on empty results and write nothing. Sections computing without study runs (reference
// renders, rasterizer agreement) are not listed; they run when the demo is assembled.
std::vector<DemoStudyRun> plan_demo(const DemoOptions& options);

// The results of one of plan_demo's runs (each has its own dir), its files already placed in
// out_dir / run.dir (a sweep's stored items, sweep/sweep.h); throws when they are missing or
// failed (that section is then reported as failed).
using DemoRunSource = std::function<Results(const DemoStudyRun& run)>;

// Runs the sections into `out_dir` (each study writes its images into a subdirectory there,
// with its results.json). A section that fails is reported on the page, not thrown. With a
// `source`, the study runs are read from it instead of run (everything else is the same).
DemoRun run_demo(const DemoOptions& options, const std::filesystem::path& out_dir, Progress& progress,
                 const DemoRunSource& source = {});

}  // namespace proxima::study
