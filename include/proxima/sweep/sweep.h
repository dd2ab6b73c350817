// A sweep: the items of a manifest run in-process or by several ranks (the MPI transport of
// the command line), stored one by one into DIR/items as they finish, and merged in manifest
// order into DIR/results.json and DIR/index.html. The merged results do not depend on how
// many ranks ran the items or which rank ran which (the studies are deterministic; timings
// aside).
#pragma once

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "proxima/core/timer.h"
#include "proxima/sweep/item.h"
#include "proxima/sweep/manifest.h"

namespace proxima::sweep {

// The bookkeeping of the rank that owns DIR: which items are left (those not already stored
// as ok for the same scene, study and options: a rerun resumes), storing each finished item,
// and a progress line per item on `log` (done / total, failures, elapsed, ETA).
class SweepCoordinator {
 public:
  SweepCoordinator(const Manifest& manifest, const std::filesystem::path& out, std::FILE* log);

  // The next item to run (manifest order) whose inputs are finished; none when every item is
  // handed out or the rest wait for inputs still running. An item whose input failed is
  // stored as failed here, not handed out.
  std::optional<size_t> next();
  bool handed_out() const { return todo_.empty(); }
  // The photo.bin bytes of item `index`'s inputs (item_inputs).
  std::vector<std::string> inputs(size_t index) const;
  // Stores item `index`'s files (store_item) and logs it; `rank` ran it.
  void finish(size_t index, const ItemFiles& files, int rank);

  size_t total() const { return manifest_.items.size(); }
  size_t skipped() const { return skipped_; }  // already finished before this run
  size_t failed() const { return failed_; }    // failed in this run

 private:
  const Manifest& manifest_;
  std::filesystem::path out_;
  std::FILE* log_;
  std::vector<size_t> todo_;        // not handed out yet, in manifest order
  std::vector<ItemState> state_;    // per item: Absent until stored
  size_t to_run_ = 0, done_ = 0, skipped_ = 0, failed_ = 0;
  Stopwatch watch_;
};

struct SweepSummary {
  size_t items = 0;   // in the manifest
  size_t failed = 0;  // stored as failed (this run or an earlier one) or never stored
};

// Reads every stored item in manifest order and writes out/results.json and out/index.html:
// each successful item's metrics as "<id>_<metric>", its tables titled "<id>: <title>", its
// images as "<id>/<role>" (files under items/<id>/), a section per item, and the table
// "sweep items" (id, study, scene, status, seconds, error). Metrics sweep_items and
// sweep_failed. `command` is the merged file's command line. A demo manifest instead gets
// the demo's own report, as `proxima demo` writes it (run_demo over the stored items, each
// run's files copied to its directory), plus the table "sweep items" and those two metrics.
SweepSummary merge_sweep(const Manifest& manifest, const std::filesystem::path& out,
                         const std::vector<std::string>& command);

// Every item in this process, one after the other (the items' own parallel loops use the
// threads), into `out`; then merge_sweep. Items run in `out`/.scratch.
SweepSummary run_sweep(const Manifest& manifest, const std::filesystem::path& out,
                       const std::vector<std::string>& command, std::FILE* log);

}  // namespace proxima::sweep
