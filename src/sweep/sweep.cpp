#include "proxima/sweep/sweep.h"

#include <system_error>

#include "proxima/core/error.h"
#include "proxima/core/progress.h"
#include "proxima/eval/html_report.h"
#include "proxima/eval/results.h"
#include "proxima/eval/results_merge.h"

namespace proxima::sweep {

namespace fs = std::filesystem;

SweepCoordinator::SweepCoordinator(const Manifest& manifest, const fs::path& out, std::FILE* log)
    : manifest_(manifest), out_(out), log_(log) {
  for (size_t i = 0; i < manifest.items.size(); ++i) {
    if (stored_item(out, manifest.items[i]).state == ItemState::Ok) ++skipped_;
    else todo_.push_back(i);
  }
  if (log_)
    std::fprintf(log_, "sweep: %zu items, %zu already finished in %s, %zu to run\n", total(), skipped_,
                 out.string().c_str(), todo_.size());
}

std::optional<size_t> SweepCoordinator::next() {
  if (next_ == todo_.size()) return std::nullopt;
  return todo_[next_++];
}

void SweepCoordinator::finish(size_t index, const ItemFiles& files, int rank) {
  const SweepItem& item = manifest_.items.at(index);
  store_item(out_, item, files);
  const ItemStatus status = item_status(files);
  ++done_;
  if (status.state != ItemState::Ok) ++failed_;
  if (!log_) return;
  const double elapsed = watch_.elapsed_ms() / 1000.0;
  const std::string what = item.id + " (" + item.scene + ") " +
                           (status.state == ItemState::Ok ? "ok" : "FAILED: " + status.error) + ", " +
                           format_duration(status.seconds) + " on rank " + std::to_string(rank) +
                           (failed_ ? ", " + std::to_string(failed_) + " failed" : "");
  std::fprintf(log_, "%s\n", progress_line("sweep", what, static_cast<int>(done_), static_cast<int>(todo_.size()),
                                           elapsed, 0)
                                 .c_str());
  std::fflush(log_);
}

namespace {

// The item's section of the report: what ran, and its images.
Section item_section(const SweepItem& item, const ItemStatus& status, const Results* results) {
  std::string text = item.study + " on " + item.scene;
  for (const auto& [name, value] : item.options) text += ", " + name + " = " + study::option_text(value);
  if (status.state != ItemState::Ok) text += "\n\nFAILED: " + status.error;
  Section s{item.id, item.id, text, {}, {}, {}};
  if (results) {
    for (const Table& t : results->tables) s.tables.push_back(item.id + ": " + t.title);
    for (const auto& [role, file] : results->images) s.images.push_back(item.id + "/" + role);
  }
  return s;
}

std::string state_name(const ItemStatus& s) {
  return s.state == ItemState::Ok ? "ok" : s.state == ItemState::Failed ? "failed" : "not run";
}

}  // namespace

SweepSummary merge_sweep(const Manifest& manifest, const fs::path& out, const std::vector<std::string>& command) {
  SweepSummary summary;
  summary.items = manifest.items.size();
  std::vector<NamedResults> runs;
  std::vector<ItemStatus> statuses;
  for (const SweepItem& item : manifest.items) {
    statuses.push_back(stored_item(out, item));
    if (statuses.back().state == ItemState::Ok)
      runs.push_back({item.id, read_results_json(out / "items" / item.id / "results.json")});
    else ++summary.failed;
  }
  // Items may come from other machines (CPU), thread counts or an earlier run of a resumed
  // sweep; their figures are merged as they are, and a different binary is said loudly.
  for (NamedResults& run : runs) {
    const Results& first = runs.front().results;
    if (run.results.commit != first.commit || run.results.build != first.build)
      std::fprintf(stderr, "sweep: WARNING: item %s was run by another binary (%s %s, not %s %s)\n", run.name.c_str(),
                   run.results.build.c_str(), run.results.commit.c_str(), first.build.c_str(), first.commit.c_str());
    run.results.commit = first.commit;
    run.results.build = first.build;
    run.results.cpu = first.cpu;
    run.results.threads = first.threads;
  }
  Results merged;
  if (!runs.empty()) merged = merge_results(runs, command);
  merged.command = command;
  merged.sections.clear();  // rebuilt below: one per item, with its images
  Table items{"sweep items", {"id", "study", "scene", "status", "seconds", "error"}, {}};
  size_t r = 0;
  for (size_t i = 0; i < manifest.items.size(); ++i) {
    const SweepItem& item = manifest.items[i];
    const Results* results = statuses[i].state == ItemState::Ok ? &runs[r++].results : nullptr;
    if (results)
      for (const auto& [role, file] : results->images)
        merged.images[item.id + "/" + role] = "items/" + item.id + "/" + file;
    merged.sections.push_back(item_section(item, statuses[i], results));
    items.rows.push_back({item.id, item.study, item.scene, state_name(statuses[i]), statuses[i].seconds,
                          statuses[i].error});
  }
  merged.tables.insert(merged.tables.begin(), items);
  merged.metrics["sweep_items"] = static_cast<double>(summary.items);
  merged.metrics["sweep_failed"] = static_cast<double>(summary.failed);
  write_results_json(out / "results.json", merged);
  write_report(out, read_results_json(out / "results.json"), "proxima sweep");
  return summary;
}

SweepSummary run_sweep(const Manifest& manifest, const fs::path& out, const std::vector<std::string>& command,
                       std::FILE* log) {
  SweepCoordinator coordinator(manifest, out, log);
  const fs::path scratch = out / ".scratch";
  while (const std::optional<size_t> i = coordinator.next())
    coordinator.finish(*i, run_item(manifest.items[*i], scratch), 0);
  std::error_code ec;
  fs::remove_all(scratch, ec);
  return merge_sweep(manifest, out, command);
}

}  // namespace proxima::sweep
