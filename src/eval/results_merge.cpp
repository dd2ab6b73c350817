// merge_results (eval/results_merge.h): the recorded runs of scripts/results.sh in one
// results.json.
#include <set>

#include "proxima/core/error.h"
#include "proxima/eval/results_merge.h"

namespace proxima {

namespace {

bool valid_run_name(const std::string& name) {
  if (name.empty() || name.size() > 32) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

// The provenance every run must share with the first one.
void check_same_provenance(const NamedResults& first, const NamedResults& run) {
  const auto differ = [&](const char* what, const std::string& a, const std::string& b) {
    if (a != b)
      fail_input("run '" + run.name + "': " + what + " '" + b + "' differs from run '" + first.name + "' ('" + a +
                 "')");
  };
  differ("commit", first.results.commit, run.results.commit);
  differ("build", first.results.build, run.results.build);
  differ("CPU", first.results.cpu, run.results.cpu);
  differ("threads", std::to_string(first.results.threads), std::to_string(run.results.threads));
}

std::string joined(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) s += (s.empty() ? "" : " ") + a;
  return s;
}

void add_run(Results& merged, const NamedResults& run) {
  const std::string& name = run.name;
  for (const auto& [metric, value] : run.results.metrics)
    if (!merged.metrics.emplace(name + "_" + metric, value).second)
      fail_input("run '" + name + "': metric '" + name + "_" + metric + "' is already another run's");
  for (Table t : run.results.tables) {
    t.title = name + ": " + t.title;
    merged.tables.push_back(std::move(t));
  }
  Section own{name, name, "", {}, {}, {joined(run.results.command)}};
  merged.sections.push_back(own);
  for (Section s : run.results.sections) {
    s.id = name + "-" + s.id;
    for (std::string& t : s.tables) t = name + ": " + t;
    for (PlotSpec& p : s.plots) p.table = name + ": " + p.table;
    s.images.clear();
    merged.sections.push_back(std::move(s));
  }
}

}  // namespace

Results merge_results(const std::vector<NamedResults>& runs, const std::vector<std::string>& command) {
  if (runs.empty()) fail_input("no runs to merge");
  Results merged;
  merged.command = command;
  merged.threads = runs.front().results.threads;
  merged.build = runs.front().results.build;
  merged.commit = runs.front().results.commit;
  merged.cpu = runs.front().results.cpu;
  std::set<std::string> names;
  for (const NamedResults& run : runs) {
    if (!valid_run_name(run.name)) fail_input("run name '" + run.name + "': use 1-32 of a-z, 0-9 and _");
    if (!names.insert(run.name).second) fail_input("run name '" + run.name + "' given twice");
    check_same_provenance(runs.front(), run);
    add_run(merged, run);
  }
  return merged;
}

}  // namespace proxima
