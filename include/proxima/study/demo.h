// The demo: every technique on the built-in scenes beside its reference, as one Results with a
// section per technique (prose, tables, images, plots and the commands that reproduce each
// figure). `proxima demo` publishes it as results.json and renders index.html from that file.
#pragma once

#include <cstdint>
#include <filesystem>
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

// Runs the sections into `out_dir` (each study writes its images into a subdirectory there,
// with its results.json). A section that fails is reported on the page, not thrown.
DemoRun run_demo(const DemoOptions& options, const std::filesystem::path& out_dir, Progress& progress);

}  // namespace proxima::study
