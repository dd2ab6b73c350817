// `proxima results merge NAME=RESULTS_JSON... --out FILE`: the recorded runs of
// scripts/results.sh in one results.json (eval/results_merge.h).
// `proxima results page RESULTS_JSON --out FILE`: docs/RESULTS.md from it (eval/results_page.h).
#include <algorithm>
#include <cstdio>

#include "command.h"
#include "proxima/core/atomic_file.h"
#include "proxima/core/error.h"
#include "proxima/eval/results_merge.h"
#include "proxima/eval/results_page.h"

namespace proxima::cli {

namespace {

struct ResultsFlags {
  std::vector<std::string> runs;  // NAME=RESULTS_JSON
  std::string input;
  std::string out;
};

int run_merge(const ResultsFlags& f) {
  std::vector<NamedResults> runs;
  for (const std::string& run : f.runs) {
    const size_t eq = run.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == run.size())
      fail_input("runs: '" + run + "' is not NAME=RESULTS_JSON");
    runs.push_back({run.substr(0, eq), read_results_json(run.substr(eq + 1))});
  }
  const Results merged = merge_results(runs, command_line());
  write_results_json(f.out, merged);
  std::printf("%s: %zu runs, %zu metrics\n", f.out.c_str(), runs.size(), merged.metrics.size());
  return 0;
}

int run_page(const ResultsFlags& f) {
  const ResultsPage page = results_page(read_results_json(f.input));
  for (const std::string& m : page.missing)
    std::fprintf(stderr, "proxima: results page: %s lacks metric %s (shown as —)\n", f.input.c_str(), m.c_str());
  write_text_file(f.out, page.markdown);
  std::printf("%s: %zu lines\n", f.out.c_str(), size_t(std::count(page.markdown.begin(), page.markdown.end(), '\n')));
  return page.missing.empty() ? 0 : 3;
}

}  // namespace

Command register_results(CLI::App& root) {
  static ResultsFlags f;
  auto* app = root.add_subcommand("results", "the measured-results page: merge recorded runs, write docs/RESULTS.md");
  app->require_subcommand(1);
  auto* merge = app->add_subcommand("merge", "join the results.json of named runs into one results.json");
  merge->add_option("runs", f.runs, "NAME=RESULTS_JSON, one per run")->required();
  merge->add_option("--out", f.out, "merged results.json to write")->required();
  auto* page = app->add_subcommand("page", "write the Markdown results page from a merged results.json");
  page->add_option("results", f.input, "merged results.json (proxima results merge)")->required();
  page->add_option("--out", f.out, "Markdown file to write")->required();
  return {app, [merge, page] {
            if (merge->parsed()) return run_merge(f);
            if (page->parsed()) return run_page(f);
            return 2;
          }};
}

}  // namespace proxima::cli
