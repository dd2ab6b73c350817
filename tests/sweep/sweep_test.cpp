// sweep/sweep.h and sweep/item.h in-process: a failing item is recorded and the others
// finish; an interrupted sweep resumes without redoing finished items; items stored by any
// rank merge in manifest order into the same results; packs round-trip.
#include "proxima/sweep/sweep.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "proxima/eval/results.h"
#include "study/study_test_util.h"
#include "test_util.h"

namespace proxima::sweep {
namespace {

namespace fs = std::filesystem;

// Three tiny reference renders (the second of a missing scene file) and a 2-point grid.
Manifest small_manifest() {
  return parse_manifest(R"({"runs": [
      {"study": "reference", "scene": ["cornell", "missing-scene.json", "room-reflector"],
       "options": {"width": 24, "height": 16, "light_samples": 1}},
      {"study": "reference", "scene": "cornell", "options": {"width": 24, "height": 16},
       "grid": {"bounces": [0, 1]}}]})",
                        "/nonexistent-dir", "small.json");
}

fs::file_time_type mtime(const fs::path& out, const std::string& id) {
  return fs::last_write_time(out / "items" / id / "item.json");
}

TEST(Sweep, FailingItemIsRecordedAndTheOthersFinish) {
  TempDir dir;
  const Manifest m = small_manifest();
  const SweepSummary s = run_sweep(m, dir.path, {"test"}, nullptr);
  EXPECT_EQ(s.items, 5u);
  EXPECT_EQ(s.failed, 1u);
  const ItemStatus bad = stored_item(dir.path, m.items[1]);
  EXPECT_EQ(bad.state, ItemState::Failed);
  EXPECT_NE(bad.error.find("missing-scene.json"), std::string::npos) << bad.error;
  EXPECT_FALSE(fs::exists(dir.path / "items" / m.items[1].id / "results.json"));
  const Results r = read_results_json(dir.path / "results.json");
  EXPECT_EQ(r.metrics.at("sweep_failed"), 1.0);
  EXPECT_TRUE(r.metrics.contains("i000_reference_coverage_pct"));
  EXPECT_TRUE(r.metrics.contains("i004_reference_coverage_pct"));
  EXPECT_FALSE(r.metrics.contains("i001_reference_coverage_pct"));
  EXPECT_EQ(r.images.at("i002_reference/color"), "items/i002_reference/color.png");
  EXPECT_TRUE(fs::exists(dir.path / "items/i002_reference/color.png"));
  EXPECT_TRUE(fs::exists(dir.path / "index.html"));
  ASSERT_FALSE(r.tables.empty());
  EXPECT_EQ(r.tables[0].title, "sweep items");
  EXPECT_EQ(std::get<std::string>(r.tables[0].rows[1][3]), "failed");
  EXPECT_FALSE(fs::exists(dir.path / ".scratch"));
}

// Two items finished, then the process "dies" (a half-written item directory left behind);
// the rerun runs only the others, and merges the same results as an uninterrupted run.
TEST(Sweep, InterruptedSweepResumesWithoutRedoingFinishedItems) {
  TempDir dir, whole;
  const Manifest m = small_manifest();
  {
    SweepCoordinator c(m, dir.path, nullptr);
    for (int k = 0; k < 2; ++k) {
      const size_t i = *c.next();
      c.finish(i, run_item(m.items[i], dir.path / ".scratch"), 0);
    }
  }
  write_file(dir.path / "items" / ("." + m.items[2].id + ".tmp") / "results.json", "{\"trunc");
  const auto first = mtime(dir.path, m.items[0].id);
  {
    SweepCoordinator c(m, dir.path, nullptr);
    EXPECT_EQ(c.skipped(), 1u);  // item 0; item 1 failed and is retried
  }
  run_sweep(m, dir.path, {"test"}, nullptr);
  EXPECT_EQ(mtime(dir.path, m.items[0].id), first);
  for (const SweepItem& item : m.items) EXPECT_NE(stored_item(dir.path, item).state, ItemState::Absent) << item.id;
  // Same figures and image bits as one uninterrupted run.
  run_sweep(m, whole.path, {"test"}, nullptr);
  const Results a = read_results_json(dir.path / "results.json");
  const Results b = read_results_json(whole.path / "results.json");
  // coverage_pct of the 4 ok items and sweep_failed (sweep_items ends in "ms": taken for a timing)
  EXPECT_EQ(expect_same_metrics(a, b), 5u);
  EXPECT_EQ(expect_same_metrics(b, a), 5u);
  expect_same_images(a, b, dir.path, whole.path);
}

TEST(Sweep, ChangedOptionsRunTheItemAgain) {
  TempDir dir;
  Manifest m = small_manifest();
  m.items.resize(1);
  run_sweep(m, dir.path, {"test"}, nullptr);
  EXPECT_EQ(stored_item(dir.path, m.items[0]).state, ItemState::Ok);
  m.items[0].options["width"] = std::int64_t{20};
  EXPECT_EQ(stored_item(dir.path, m.items[0]).state, ItemState::Absent);
  SweepCoordinator c(m, dir.path, nullptr);
  EXPECT_EQ(c.skipped(), 0u);
}

TEST(SweepItem, PackRoundTripsAndRejectsDamage) {
  const ItemFiles files{{{"item.json", "{}"}, {"views/a.png", std::string("\0\x01\xff", 3)}, {"empty", ""}}};
  const std::string packed = pack_item(files);
  EXPECT_EQ(unpack_item(packed).files, files.files);
  EXPECT_THROW(unpack_item(packed.substr(0, packed.size() - 1)), std::runtime_error);
  EXPECT_THROW(unpack_item(packed + "x"), std::runtime_error);
  EXPECT_THROW(unpack_item(pack_item({{{"../evil", "x"}}})), std::runtime_error);
  EXPECT_THROW(unpack_item(std::string(3, '\0')), std::runtime_error);
}

}  // namespace
}  // namespace proxima::sweep
