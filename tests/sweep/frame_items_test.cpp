// Runs split into frame parts (study/frame_split.h, sweep/frame_parts.h): a cluster_reflect
// and a visibility run, split into frame-part items and merged by their run's item, give the
// study run in one call bit for bit — deterministic metrics, deterministic table cells and
// every image file — also with a part that has no frames and with the image frame in a
// later part; a rerun redoes only the missing parts; a failing part fails its run's item.
#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <regex>
#include <string>

#include "proxima/scene/load.h"
#include "proxima/study/catalog.h"
#include "proxima/study/frame_split.h"
#include "proxima/sweep/frame_parts.h"
#include "proxima/sweep/sweep.h"
#include "study/study_test_util.h"
#include "test_util.h"

namespace proxima::sweep {
namespace {

namespace fs = std::filesystem;

// Five frames of room-reflector's first path with compare and SSR, images of frame 3 (in the
// second of three parts); five viewpoints of rooms in three parts, and two in three parts
// (the first part has none).
constexpr const char* kManifest = R"({"runs": [
  {"study": "cluster_reflect", "scene": "room-reflector", "frame_items": 3,
   "options": {"width": 48, "height": 32, "path": "0", "frames": 5, "ss": 1, "cube_size": 16,
               "compare": true, "ssr": true, "image_frame": 3}},
  {"study": "visibility", "scene": "rooms", "frame_items": 3,
   "options": {"width": 96, "height": 72, "frames": 5, "selfcheck_rays": 200}},
  {"study": "visibility", "scene": "rooms", "frame_items": 3,
   "options": {"width": 96, "height": 72, "frames": 2, "selfcheck_rays": 200, "oracle": false}}
]})";

const std::regex kTiming("_ms|^ms|ms$|fps|speedup");

// The same tables, cell for cell outside timing columns (and the step-time table).
size_t expect_same_tables(const Results& a, const Results& b) {
  size_t compared = 0;
  EXPECT_EQ(a.tables.size(), b.tables.size());
  for (size_t t = 0; t < std::min(a.tables.size(), b.tables.size()); ++t) {
    const Table &x = a.tables[t], &y = b.tables[t];
    EXPECT_EQ(x.title, y.title);
    EXPECT_EQ(x.columns, y.columns) << x.title;
    EXPECT_EQ(x.rows.size(), y.rows.size()) << x.title;
    if (x.columns != y.columns || x.rows.size() != y.rows.size() || x.title.find("in ms") != std::string::npos)
      continue;
    for (size_t c = 0; c < x.columns.size(); ++c) {
      if (std::regex_search(x.columns[c], kTiming)) continue;
      for (size_t r = 0; r < x.rows.size(); ++r) {
        EXPECT_EQ(x.rows[r][c], y.rows[r][c]) << x.title << " row " << r << " " << x.columns[c];
        ++compared;
      }
    }
  }
  return compared;
}

// Every file a study wrote, by name.
std::map<std::string, std::string> study_files(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(e.path(), dir).generic_string();
    if (e.is_regular_file() && name != "item.json" && name != "results.json") files[name] = file_bytes(e.path());
  }
  return files;
}

// Item `index` (a run's item) against its study called in one process.
void expect_item_is_the_study_run(const Manifest& m, size_t index, const fs::path& out, const fs::path& direct) {
  const SweepItem& item = m.items[index];
  const fs::path dir = out / "items" / item.id;
  const Results split = read_results_json(dir / "results.json");
  const Results whole = study::run_study(item.study, load_scene(item.scene), item.options, {direct / item.id});
  EXPECT_GT(expect_same_metrics(whole, split), 15u) << item.id;
  EXPECT_GT(expect_same_metrics(split, whole), 15u) << item.id;
  EXPECT_GT(expect_same_tables(whole, split), 10u) << item.id;
  EXPECT_EQ(whole.images, split.images) << item.id;
  const std::map<std::string, std::string> a = study_files(direct / item.id), b = study_files(dir);
  EXPECT_EQ(a.size(), b.size()) << item.id;
  for (const auto& [name, bytes] : a) {
    const std::string& file = name;
    EXPECT_TRUE(b.contains(file) && b.at(file) == bytes) << item.id << ": " << file;
  }
}

TEST(SweepFrames, FramePartsCoverEveryFrameOnceInOrder) {
  for (int n = 0; n <= 13; ++n)
    for (int k = 1; k <= 6; ++k) {
      int next = 0, smallest = n, largest = 0;
      for (int i = 0; i < k; ++i) {
        const auto [first, last] = study::frame_span({i, k}, n);
        EXPECT_EQ(first, next) << n << " frames, part " << i << " of " << k;
        smallest = std::min(smallest, last - first);
        largest = std::max(largest, last - first);
        next = last;
      }
      EXPECT_EQ(next, n) << n << " frames in " << k;
      EXPECT_LE(largest - smallest, 1) << n << " frames in " << k;
    }
}

TEST(SweepFrames, PartBytesRoundTripAndMalformedOnesAreRefused) {
  FramePartData part;
  part.figures.series = {{1.0, -0.0, 1e300}, {}, {std::numeric_limits<double>::infinity()}};
  part.images = {{"cluster", "cluster.png"}};
  part.files.files = {{"cluster.png", std::string("\x89PNG\0bytes", 10)}};
  const std::string bytes = pack_frame_part(part);
  const FramePartData back = unpack_frame_part(bytes);
  EXPECT_EQ(back.figures.series, part.figures.series);
  EXPECT_EQ(back.images, part.images);
  EXPECT_EQ(back.files.files, part.files.files);
  for (size_t cut : {size_t(0), size_t(8), bytes.size() / 2, bytes.size() - 1})
    EXPECT_THROW(unpack_frame_part(std::string_view(bytes).substr(0, cut)), std::runtime_error) << cut;
  EXPECT_THROW(unpack_frame_part(bytes + "x"), std::runtime_error);
  EXPECT_THROW(unpack_frame_part(pack_item(part.files)), std::runtime_error);  // no figures
  study::FrameFigures all;
  study::append_figures(all, part.figures);
  study::append_figures(all, part.figures);
  EXPECT_EQ(all.series[0].size(), 6u);
  EXPECT_THROW(study::append_figures(all, study::FrameFigures{{{1.0}}}), std::runtime_error);
}

TEST(SweepFrames, ARunBecomesFramePartsAndTheRunsItem) {
  const Manifest m = parse_manifest(kManifest, ".", "frames.json");
  ASSERT_EQ(m.items.size(), 12u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(m.items[size_t(k)].id, "i00" + std::to_string(k) + "_cluster_reflect_part");
    EXPECT_EQ(m.items[size_t(k)].frame_part, k);
    EXPECT_EQ(m.items[size_t(k)].frame_parts, 3);
    EXPECT_TRUE(m.items[size_t(k)].is_part());
  }
  EXPECT_EQ(m.items[3].id, "i003_cluster_reflect");
  EXPECT_EQ(m.items[3].frame_part, -1);
  EXPECT_EQ(m.items[3].frame_parts, 3);
  EXPECT_EQ(m.items[3].inputs, (std::vector<size_t>{0, 1, 2}));
  EXPECT_EQ(m.items[7].inputs, (std::vector<size_t>{4, 5, 6}));
  EXPECT_EQ(m.items[11].id, "i011_visibility");
}

TEST(SweepFrames, SplitRunsGiveTheStudyRunsResultsBitForBitAndResume) {
  TempDir dir;
  const Manifest m = parse_manifest(kManifest, ".", "frames.json");
  const fs::path out = dir.path / "sweep";
  EXPECT_EQ(run_sweep(m, out, {"test"}, nullptr).failed, 0u);
  for (size_t run : {3u, 7u, 11u}) expect_item_is_the_study_run(m, run, out, dir.path / "direct");

  // A rerun after losing the cluster run's middle part and its run's item redoes those two.
  std::map<std::string, fs::file_time_type> times;
  for (const SweepItem& item : m.items) times[item.id] = fs::last_write_time(out / "items" / item.id / "item.json");
  fs::remove_all(out / "items" / m.items[1].id);
  fs::remove_all(out / "items" / m.items[3].id);
  EXPECT_EQ(SweepCoordinator(m, out, nullptr).skipped(), m.items.size() - 2);
  EXPECT_EQ(run_sweep(m, out, {"test"}, nullptr).failed, 0u);
  for (const SweepItem& item : m.items) {
    if (item.id != m.items[1].id && item.id != m.items[3].id) {
      EXPECT_EQ(fs::last_write_time(out / "items" / item.id / "item.json"), times[item.id]) << item.id;
    }
  }
  expect_item_is_the_study_run(m, 3, out, dir.path / "direct2");
}

TEST(SweepFrames, AFailedPartFailsItsRunsItemAndTheSweepGoesOn) {
  TempDir dir;
  // frames 100001 is over the study's limit: every part fails, and so does the run's item.
  const Manifest m = parse_manifest(R"({"runs": [
      {"study": "cluster_reflect", "scene": "room-reflector", "frame_items": 2,
       "options": {"path": "0", "frames": 100001}},
      {"study": "reference", "scene": "cornell", "options": {"width": 16, "height": 12}}]})",
                                    ".", "bad.json");
  ASSERT_EQ(m.items.size(), 4u);
  EXPECT_EQ(run_sweep(m, dir.path, {"test"}, nullptr).failed, 3u);
  EXPECT_NE(stored_item(dir.path, m.items[0]).error.find("--frames"), std::string::npos);
  EXPECT_NE(stored_item(dir.path, m.items[2]).error.find("i000_cluster_reflect_part"), std::string::npos);
  EXPECT_EQ(stored_item(dir.path, m.items[3]).state, ItemState::Ok);
}

}  // namespace
}  // namespace proxima::sweep
