// `proxima demo`: the main job on the built-in scenes (study/demo.h), written as
// out/demo/results.json and out/demo/index.html, rendered from that results.json so the page
// shows its numbers.
#include <cstdio>

#include "command.h"
#include "proxima/eval/html_report.h"
#include "proxima/core/atomic_file.h"
#include "proxima/study/demo.h"
#include "proxima/sweep/manifest.h"

namespace proxima::cli {

Command register_demo(CLI::App& root) {
  static CommonOptions common;
  static study::DemoOptions o;
  auto* app = root.add_subcommand("demo", "run the main job on the built-in scenes → results.json + index.html");
  common.out = "out/demo";
  add_common_flags(app, common, {});
  app->add_flag("--full", o.full, "the papers' settings (hours) instead of the ≤ 10-minute ones");
  app->add_option("--only", o.only, "run only these sections (comma-separated ids)")->delimiter(',');
  static std::string manifest;
  app->add_option("--manifest", manifest,
                  "write the demo's study runs as a sweep manifest to this file and stop (run it with proxima sweep)");

  return {app, [] {
            set_common_options(common, o);
            o.out_arg = common.out;
            study::validate(o);
            if (!manifest.empty()) {
              write_text_file(manifest, sweep::demo_manifest_json(o));
              std::fprintf(stderr, "demo: manifest → %s (proxima sweep %s --out DIR)\n", manifest.c_str(),
                           manifest.c_str());
              return 0;
            }
            const auto out = prepare_out_dir(common.out);
            Progress progress;
            study::DemoRun run = study::run_demo(o, out, progress);
            run.results.command = command_line();
            publish_results(out, run.results);
            // The page is rendered from the file just written, so it cannot disagree with it.
            write_report(out, read_results_json(out / "results.json"), "proxima demo");
            std::fprintf(stderr, "demo: report → %s (%.0f s)\n", (out / "index.html").c_str(),
                         run.results.metrics["demo_seconds"]);
            return run.failed_sections ? 1 : 0;
          }};
}

}  // namespace proxima::cli
