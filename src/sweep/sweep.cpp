#include "proxima/sweep/sweep.h"

#include <stdexcept>
#include <system_error>

#include "proxima/core/error.h"
#include "proxima/core/progress.h"
#include "proxima/eval/html_report.h"
#include "proxima/eval/results.h"
#include "proxima/eval/results_merge.h"
#include "proxima/study/demo.h"

namespace proxima::sweep {

namespace fs = std::filesystem;

SweepCoordinator::SweepCoordinator(const Manifest& manifest, const fs::path& out, std::FILE* log)
    : manifest_(manifest), out_(out), log_(log), state_(manifest.items.size(), ItemState::Absent) {
  for (size_t i = 0; i < manifest.items.size(); ++i) {
    if (stored_item(out, manifest.items[i]).state == ItemState::Ok) {
      state_[i] = ItemState::Ok;
      ++skipped_;
    } else {
      todo_.push_back(i);
    }
  }
  to_run_ = todo_.size();
  if (log_)
    std::fprintf(log_, "sweep: %zu items, %zu already finished in %s, %zu to run\n", total(), skipped_,
                 out.string().c_str(), todo_.size());
}

std::optional<size_t> SweepCoordinator::next() {
  for (size_t k = 0; k < todo_.size();) {
    const size_t i = todo_[k];
    std::string failed_input;
    bool ready = true;
    for (size_t in : manifest_.items[i].inputs) {
      if (state_[in] == ItemState::Failed && failed_input.empty()) failed_input = manifest_.items[in].id;
      ready = ready && state_[in] == ItemState::Ok;
    }
    if (!failed_input.empty()) {
      todo_.erase(todo_.begin() + std::ptrdiff_t(k));
      finish(i, failed_item(manifest_.items[i], "input item " + failed_input + " failed"), 0);
      continue;
    }
    if (ready) {
      todo_.erase(todo_.begin() + std::ptrdiff_t(k));
      return i;
    }
    ++k;
  }
  return std::nullopt;
}

std::vector<std::string> SweepCoordinator::inputs(size_t index) const {
  return item_inputs(manifest_, out_, manifest_.items.at(index));
}

void SweepCoordinator::finish(size_t index, const ItemFiles& files, int rank) {
  const SweepItem& item = manifest_.items.at(index);
  store_item(out_, item, files);
  const ItemStatus status = item_status(files);
  state_.at(index) = status.state == ItemState::Ok ? ItemState::Ok : ItemState::Failed;
  ++done_;
  if (status.state != ItemState::Ok) ++failed_;
  if (!log_) return;
  const double elapsed = watch_.elapsed_ms() / 1000.0;
  const std::string what = item.id + " (" + item.scene + ") " +
                           (status.state == ItemState::Ok ? "ok" : "FAILED: " + status.error) + ", " +
                           format_duration(status.seconds) + " on rank " + std::to_string(rank) +
                           (failed_ ? ", " + std::to_string(failed_) + " failed" : "");
  std::fprintf(log_, "%s\n", progress_line("sweep", what, static_cast<int>(done_), static_cast<int>(to_run_),
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

// Every item's results side by side, a section per study item.
Results merge_items(const Manifest& manifest, const std::vector<ItemStatus>& statuses, std::vector<NamedResults>& runs,
                    const std::vector<std::string>& command) {
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
  merged.sections.clear();  // rebuilt below: one per item, with its images
  size_t r = 0;
  for (size_t i = 0; i < manifest.items.size(); ++i) {
    const SweepItem& item = manifest.items[i];
    if (item.is_part()) continue;  // its photograph's mapping or frame figures went into its run's item
    const Results* results = statuses[i].state == ItemState::Ok ? &runs[r++].results : nullptr;
    if (results)
      for (const auto& [role, file] : results->images)
        merged.images[item.id + "/" + role] = "items/" + item.id + "/" + file;
    merged.sections.push_back(item_section(item, statuses[i], results));
  }
  return merged;
}

}  // namespace

namespace {

Table items_table(const Manifest& manifest, const std::vector<ItemStatus>& statuses) {
  Table items{"sweep items", {"id", "study", "scene", "status", "seconds", "error"}, {}};
  for (size_t i = 0; i < manifest.items.size(); ++i) {
    const SweepItem& item = manifest.items[i];
    const std::string what = item.photo >= 0        ? item.study + " photograph " + std::to_string(item.photo)
                             : item.frame_part >= 0 ? item.study + " frames " + std::to_string(item.frame_part + 1) +
                                                          "/" + std::to_string(item.frame_parts)
                                                    : item.study;
    items.rows.push_back({item.id, what,
                          item.scene, state_name(statuses[i]), statuses[i].seconds, statuses[i].error});
  }
  return items;
}

// The demo's report from the stored items: each run's files copied to the directory the
// demo gives it, then run_demo reading them back instead of running the studies.
Results merge_demo(const Manifest& manifest, const fs::path& out, const std::vector<ItemStatus>& statuses) {
  const study::DemoRunSource source = [&](const study::DemoStudyRun& run) {
    const auto it = manifest.demo_items.find(run.dir);
    if (it == manifest.demo_items.end()) throw std::runtime_error("sweep: no item for demo run " + run.dir);
    const SweepItem& item = manifest.items[it->second];
    const ItemStatus& status = statuses[it->second];
    if (status.state != ItemState::Ok)
      throw std::runtime_error("item " + item.id + " " + state_name(status) +
                               (status.error.empty() ? "" : ": " + status.error));
    const fs::path from = out / "items" / item.id, to = out / run.dir;
    fs::create_directories(to);
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(from)) {
      const fs::path rel = fs::relative(e.path(), from);
      if (e.is_directory()) fs::create_directories(to / rel);
      else if (rel != "item.json") fs::copy_file(e.path(), to / rel, fs::copy_options::overwrite_existing);
    }
    return read_results_json(to / "results.json");
  };
  Progress progress(stderr, false);
  study::DemoRun run = study::run_demo(*manifest.demo, out, progress, source);
  return run.results;
}

}  // namespace

SweepSummary merge_sweep(const Manifest& manifest, const fs::path& out, const std::vector<std::string>& command) {
  SweepSummary summary;
  summary.items = manifest.items.size();
  std::vector<NamedResults> runs;
  std::vector<ItemStatus> statuses;
  for (const SweepItem& item : manifest.items) {
    statuses.push_back(stored_item(out, item));
    if (statuses.back().state != ItemState::Ok) ++summary.failed;
    else if (!item.is_part() && !manifest.demo)
      runs.push_back({item.id, read_results_json(out / "items" / item.id / "results.json")});
  }
  Results merged;
  if (manifest.demo) {
    merged = merge_demo(manifest, out, statuses);
  } else {
    merged = merge_items(manifest, statuses, runs, command);
  }
  merged.command = command;
  merged.tables.insert(merged.tables.begin(), items_table(manifest, statuses));
  merged.metrics["sweep_items"] = static_cast<double>(summary.items);
  merged.metrics["sweep_failed"] = static_cast<double>(summary.failed);
  write_results_json(out / "results.json", merged);
  write_report(out, read_results_json(out / "results.json"), manifest.demo ? "proxima demo" : "proxima sweep");
  return summary;
}

SweepSummary run_sweep(const Manifest& manifest, const fs::path& out, const std::vector<std::string>& command,
                       std::FILE* log) {
  SweepCoordinator coordinator(manifest, out, log);
  const fs::path scratch = out / ".scratch";
  // Inputs come before their item in a manifest: in one process nothing ever waits.
  while (const std::optional<size_t> i = coordinator.next())
    coordinator.finish(*i, run_item(manifest.items[*i], scratch, coordinator.inputs(*i)), 0);
  std::error_code ec;
  fs::remove_all(scratch, ec);
  return merge_sweep(manifest, out, command);
}

}  // namespace proxima::sweep
