// `proxima demo` sections: one function per technique, each adding its prose, tables,
// images, plots and reproducing commands to the report's Results. A technique joins the
// demo with one demo_<technique>.cpp and one line in demo_sections() (demo.cpp).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "proxima/core/image.h"
#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/study/demo.h"
#include "proxima/study/study.h"

namespace proxima::study::demo {

struct Context {
  bool full = false;  // the papers' settings instead of the ≤ 10-minute ones
  int threads = 0;    // shown in every reproducing command (0 = all cores)
  uint64_t seed = 1;
  int width = 512, height = 512;  // reference renders
  std::filesystem::path out;      // the report's directory
  std::string out_arg;            // --out as given, for the reproducing commands
  Results* results = nullptr;
  Progress* progress = nullptr;
  // Planning (plan_demo): study runs are listed here instead of run, and no file is read or
  // written (images read back are 1×1 black).
  std::vector<DemoStudyRun>* plan = nullptr;
  const DemoRunSource* source = nullptr;  // non-null: study runs are read from it
};

// One technique's section. `steps` is its number of progress steps (study runs).
struct SectionDef {
  std::string id;
  std::string stage;  // progress label
  std::function<int(const Context&)> steps;
  std::function<void(Context&)> run;
  bool studies = true;  // its figures come from study runs (run_study); false: computed by the section
};

// Every section, in page order (demo.cpp).
std::vector<SectionDef> demo_sections();

// The sections themselves (demo_<technique>.cpp).
void reference_section(Context& c);
void raster_section(Context& c);
void sampling_section(Context& c);
void envmap_section(Context& c);
void cluster_section(Context& c);
void visibility_section(Context& c);
void shadows_section(Context& c);
void temporal_section(Context& c);
void gibr_section(Context& c);
void bench_section(Context& c);  // after the others: reuses their demo-settings timings
int sampling_steps(const Context& c);
int envmap_steps(const Context& c);
int cluster_steps(const Context& c);
int visibility_steps(const Context& c);
int shadows_steps(const Context& c);
int temporal_steps(const Context& c);

// A finished study run: its results and where they are, relative to the report.
struct StudyRun {
  Results results;
  std::string dir;      // relative to Context::out
  std::string command;  // the shell command reproducing it
};

// Runs one study in-process as one progress step: `study` writes its images into
// <out>/<dir> and returns its results, which are also written there as results.json.
// `args` is the command reproducing the run (shown in the report, with `--out <dir>` and
// `--threads N` appended); the study must be called with the options those flags give.
StudyRun run_study(Context& c, const std::string& dir, std::vector<std::string> args,
                   const std::function<Results(const study::StudyOutput&)>& study);

// A metric of a study run, NaN if it did not write it.
double metric(const Results& r, const std::string& name);

// Adds image file `file` (relative to the report) under `role` to the report and section.
void add_image(Context& c, Section& s, const std::string& role, const std::string& file);

// Reads an 8-bit image a study wrote (linear RGB).
ImageF read_study_image(const Context& c, const std::string& file);

// The size × size window (on a stride of size / 8) with the largest summed error.
struct Window {
  int x = 0, y = 0, size = 0;
};
Window worst_window(const ImageF& error, int size);

// The window of `image`, enlarged `zoom`× (nearest neighbour, so pixels stay visible).
ImageF crop_zoom(const ImageF& image, const Window& w, int zoom);

// Images side by side, each box-filtered down by `shrink` (heights must match), 4 px gaps.
ImageF side_by_side(const std::vector<ImageF>& images, int shrink);

// Writes `image` as <out>/<file> (PNG, linear → sRGB) and adds it as `role`.
void write_image(Context& c, Section& s, const std::string& role, const std::string& file, const ImageF& image);

// Adds the heat-map legend (once per report) to the section.
void add_heatmap_legend(Context& c, Section& s, float max_error);

// "12.3" — short numbers for table cells that combine several values.
std::string fixed(double v, int decimals);

}  // namespace proxima::study::demo
