#include "proxima/study/demo.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "demo_sections.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
#include "proxima/core/timer.h"

namespace proxima::study {

namespace demo {

std::vector<SectionDef> demo_sections() {
  auto one = [](const Context&) { return 1; };
  return {
      {"reference", "reference renders", [](const Context&) { return 2; }, reference_section, false},
      {"raster", "rasterizer vs Embree", one, raster_section, false},
      {"sampling", "depth-image sampling", sampling_steps, sampling_section},
      {"shadows", "soft shadows", shadows_steps, shadows_section},
      {"envmap", "environment maps", envmap_steps, envmap_section},
      {"cluster", "cluster reflections", cluster_steps, cluster_section},
      {"temporal", "temporal reuse", temporal_steps, temporal_section},
      {"visibility", "visibility maps", visibility_steps, visibility_section},
      {"gibr", "image-based rendering", one, gibr_section},
      {"bench", "techniques vs Embree", one, bench_section},
  };
}

}  // namespace demo

std::vector<std::string> demo_section_ids() {
  std::vector<std::string> ids;
  for (const demo::SectionDef& s : demo::demo_sections()) ids.push_back(s.id);
  return ids;
}

void validate(const DemoOptions& o) {
  const std::vector<std::string> ids = demo_section_ids();
  for (const std::string& id : o.only)
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) {
      std::string list;
      for (const std::string& s : ids) list += (list.empty() ? "" : ", ") + s;
      fail_input("--only: unknown section '" + id + "' (" + list + ")");
    }
  require_at_least(o.threads, 0, "--threads");
}

namespace {

// The page's first section: how this run was made and how long it took.
Section run_section(const DemoOptions& o, const Table& timing, double seconds, int threads) {
  std::ostringstream text;
  text << (o.full ? "Full run: the papers' settings (resolutions, frame counts, repetitions)."
                  : "Quick run: reduced resolutions, frame counts and repetitions, chosen so the whole "
                    "demo finishes in at most 10 minutes on 2 cores; `proxima demo --full` runs the "
                    "papers' settings. Each section states its settings and the exact commands.")
       << "\n\nThis run took " << demo::fixed(seconds / 60.0, 1) << " minutes with " << threads
       << " threads (table below; wall time on a possibly shared machine).";
  return {"run", "This run", text.str(), {timing.title}, {}, {"proxima demo" + std::string(o.full ? " --full" : "")}};
}

}  // namespace

namespace {

demo::Context context(const DemoOptions& o, const std::filesystem::path& out_dir, Results& results,
                      Progress& progress) {
  demo::Context c;
  c.full = o.full;
  c.threads = o.threads;
  c.seed = o.seed;
  c.width = o.width;
  c.height = o.height;
  c.out = out_dir;
  c.out_arg = o.out_arg.empty() ? out_dir.string() : o.out_arg;
  c.results = &results;
  c.progress = &progress;
  return c;
}

bool selected(const DemoOptions& o, const demo::SectionDef& s) {
  return o.only.empty() || std::find(o.only.begin(), o.only.end(), s.id) != o.only.end();
}

}  // namespace

std::vector<DemoStudyRun> plan_demo(const DemoOptions& o) {
  validate(o);
  Results results;
  Progress silent([](const ProgressEvent&) {});
  std::vector<DemoStudyRun> plan;
  demo::Context c = context(o, "demo-plan", results, silent);
  c.plan = &plan;
  for (const demo::SectionDef& s : demo::demo_sections())
    if (s.studies && selected(o, s)) s.run(c);
  return plan;
}

DemoRun run_demo(const DemoOptions& o, const std::filesystem::path& out_dir, Progress& progress,
                 const DemoRunSource& source) {
  validate(o);
  ThreadLimit limit(o.threads);
  DemoRun run;
  run.results.threads = active_threads();
  demo::Context c = context(o, out_dir, run.results, progress);
  if (source) c.source = &source;

  Stopwatch total;
  Table timing{"demo stages", {"section", "seconds"}, {}};
  for (const demo::SectionDef& s : demo::demo_sections()) {
    if (!selected(o, s)) continue;
    Stopwatch w;
    progress.begin(s.stage, s.steps(c));
    try {
      s.run(c);
    } catch (const std::exception& e) {
      // One technique failing must not lose the others' figures: the page says so.
      ++run.failed_sections;
      progress.end();
      std::fprintf(stderr, "demo: section %s FAILED: %s\n", s.id.c_str(), e.what());
      run.results.sections.push_back({s.id + "-failed", s.stage + " (failed)",
                                      std::string("This section failed in this run: ") + e.what(), {}, {}, {}});
    }
    progress.end();
    timing.rows.push_back({s.id, w.elapsed_ms() / 1000.0});
  }
  const double seconds = total.elapsed_ms() / 1000.0;
  timing.rows.push_back({std::string("total"), seconds});
  run.results.metrics["demo_seconds"] = seconds;
  run.results.tables.push_back(timing);
  run.results.sections.insert(run.results.sections.begin(), run_section(o, timing, seconds, run.results.threads));
  return run;
}

}  // namespace proxima::study
