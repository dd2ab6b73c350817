// `proxima demo`: the main job on the built-in scenes, written as out/demo/results.json and
// out/demo/index.html (rendered from that results.json, so the page shows its numbers).
// Each technique is one section (demo.h); most run the technique's own subcommand as a
// child process, so every figure on the page has the exact command that reproduces it.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "command.h"
#include "demo.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/eval/html_report.h"

namespace proxima::cli {

namespace demo {

std::vector<SectionDef> demo_sections() {
  auto one = [](const Context&) { return 1; };
  return {
      {"reference", "reference renders", [](const Context&) { return 2; }, reference_section},
      {"raster", "rasterizer vs Embree", one, raster_section},
      {"sampling", "depth-image sampling", sampling_steps, sampling_section},
      {"shadows", "soft shadows", shadows_steps, shadows_section},
      {"envmap", "environment maps", envmap_steps, envmap_section},
      {"cluster", "cluster reflections", cluster_steps, cluster_section},
      {"temporal", "temporal reuse", temporal_steps, temporal_section},
      {"visibility", "visibility maps", visibility_steps, visibility_section},
      {"gibr", "image-based rendering", one, gibr_section},
  };
}

}  // namespace demo

namespace {

struct DemoFlags {
  CommonOptions common;
  bool full = false;
  std::vector<std::string> only;
};

}  // namespace

Command register_demo(CLI::App& root) {
  static DemoFlags f;
  static CLI::App* root_app = &root;
  auto* app = root.add_subcommand("demo", "run the main job on the built-in scenes → results.json + index.html");
  add_size_flags(app, f.common);
  add_threads_flag(app, f.common);
  add_seed_flag(app, f.common);
  add_out_flag(app, f.common, false);
  f.common.out = "out/demo";
  app->add_flag("--full", f.full, "the papers' settings (hours) instead of the ≤ 10-minute ones");
  app->add_option("--only", f.only, "run only these sections (comma-separated ids)")->delimiter(',');

  return {app, [] {
            const std::vector<demo::SectionDef> all = demo::demo_sections();
            for (const std::string& id : f.only)
              if (std::none_of(all.begin(), all.end(), [&](const demo::SectionDef& s) { return s.id == id; })) {
                std::string ids;
                for (const auto& s : all) ids += (ids.empty() ? "" : ", ") + s.id;
                fail_input("--only: unknown section '" + id + "' (" + ids + ")");
              }
            if (f.common.threads < 0) fail_input("--threads: must be ≥ 0");
            ThreadLimit limit(f.common.threads);
            auto out = prepare_out_dir(f.common.out);
            Results results;
            results.command = command_line();
            results.threads = active_threads();
            Progress progress;
            demo::Context c;
            c.full = f.full;
            c.threads = f.common.threads;
            c.seed = f.common.seed;
            c.width = f.common.width;
            c.height = f.common.height;
            c.out = out;
            c.out_arg = f.common.out;
            c.results = &results;
            c.progress = &progress;
            c.root = root_app;

            Stopwatch total;
            Table timing{"demo stages", {"section", "seconds"}, {}};
            int failed = 0;
            for (const demo::SectionDef& s : all) {
              if (!f.only.empty() && std::find(f.only.begin(), f.only.end(), s.id) == f.only.end()) continue;
              Stopwatch w;
              progress.begin(s.stage, s.steps(c));
              try {
                s.run(c);
              } catch (const std::exception& e) {
                // One technique failing must not lose the others' figures: the page says so.
                ++failed;
                progress.end();
                std::fprintf(stderr, "demo: section %s FAILED: %s\n", s.id.c_str(), e.what());
                results.sections.push_back({s.id + "-failed", s.stage + " (failed)",
                                            std::string("This section failed in this run: ") + e.what(), {}, {}, {}});
              }
              progress.end();
              timing.rows.push_back({s.id, w.elapsed_ms() / 1000.0});
            }
            const double seconds = total.elapsed_ms() / 1000.0;
            timing.rows.push_back({std::string("total"), seconds});
            results.metrics["demo_seconds"] = seconds;
            results.tables.push_back(timing);
            std::ostringstream text;
            text << (f.full ? "Full run: the papers' settings (resolutions, frame counts, repetitions)."
                            : "Quick run: reduced resolutions, frame counts and repetitions, chosen so the whole "
                              "demo finishes in at most 10 minutes on 2 cores; `proxima demo --full` runs the "
                              "papers' settings. Each section states its settings and the exact commands.")
                 << "\n\nThis run took " << demo::fixed(seconds / 60.0, 1) << " minutes with " << results.threads
                 << " threads (table below; wall time on a possibly shared machine).";
            results.sections.insert(results.sections.begin(),
                                    {"run", "This run", text.str(), {timing.title}, {}, {"proxima demo" + std::string(f.full ? " --full" : "")}});
            publish_results(out, results);
            // The page is rendered from the file just written, so it cannot disagree with it.
            write_report(out, read_results_json(out / "results.json"), "proxima demo");
            std::fprintf(stderr, "demo: report → %s (%.0f s)\n", (out / "index.html").c_str(), seconds);
            return failed ? 1 : 0;
          }};
}

}  // namespace proxima::cli
