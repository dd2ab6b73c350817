// `proxima sweep` with runs split into frame parts ("frame_items"): a cluster_reflect and a
// visibility run split into parts give, in-process and under `mpirun -np 1` and `-np 3`,
// the same deterministic metrics and image bytes as the same runs unsplit.
#include <gtest/gtest.h>

#include <string>

#include "cli/cli_util.h"
#include "proxima/eval/results.h"
#include "study/study_test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

// The runs; FRAMES is "frame_items": 3 or nothing.
std::string manifest(const std::string& frames) {
  return R"({"runs": [
  {"study": "cluster_reflect", "scene": "room-reflector", )" + frames + R"(
   "options": {"width": 40, "height": 30, "path": "0", "frames": 4, "ss": 1, "cube_size": 16, "compare": true}},
  {"study": "visibility", "scene": "rooms", )" + frames + R"(
   "options": {"width": 80, "height": 60, "frames": 4, "selfcheck_rays": 200}}
]})";
}

// The run items' results of two sweeps (items `a` of one, `b` of the other) are the same.
void expect_same_items(const fs::path& a, const std::string& id_a, const fs::path& b, const std::string& id_b) {
  const Results ra = read_results_json(a / "items" / id_a / "results.json");
  const Results rb = read_results_json(b / "items" / id_b / "results.json");
  EXPECT_GT(expect_same_metrics(ra, rb), 15u) << id_a;
  EXPECT_GT(expect_same_metrics(rb, ra), 15u) << id_a;
  expect_same_images(ra, rb, a / "items" / id_a, b / "items" / id_b);
  EXPECT_GE(ra.images.size(), 2u) << id_a;
  for (const auto& e : fs::directory_iterator(a / "items" / id_a)) {  // every map_NNN file too
    if (e.path().extension() == ".png" || e.path().extension() == ".svg") {
      EXPECT_EQ(file_bytes(e.path()), file_bytes(b / "items" / id_b / e.path().filename())) << e.path();
    }
  }
}

TEST(SweepFramesCli, SplitRunsGiveTheUnsplitResultsInProcessAndOnRanks) {
  TempDir dir;
  write_file(dir.path / "whole.json", manifest(""));
  write_file(dir.path / "split.json", manifest(R"("frame_items": 3,)"));
  const auto sweep = [&](const std::string& m, const std::string& out, const std::string& launcher = "") {
    const RunResult r = run_cli("sweep " + (dir.path / m).string() + " --threads 1 --out " + (dir.path / out).string(),
                                launcher);
    EXPECT_EQ(r.exit_code, 0) << out << ": " << r.output;
  };
  sweep("whole.json", "whole");
  sweep("split.json", "local");
  const Results merged = read_results_json(dir.path / "local" / "results.json");
  EXPECT_EQ(merged.metrics.at("sweep_items"), 8.0);  // 3 parts and the run's item, twice
  expect_same_items(dir.path / "whole", "i000_cluster_reflect", dir.path / "local", "i003_cluster_reflect");
  expect_same_items(dir.path / "whole", "i001_visibility", dir.path / "local", "i007_visibility");
#ifndef PROXIMA_MPIEXEC
  GTEST_SKIP() << "built without MPI (PROXIMA_MPI): only the in-process sweeps";
#else
  // OpenMPI does not free its own allocations at exit: LeakSanitizer (sanitizer builds) would
  // report them and turn the ranks' exit code non-zero.
  const std::string mpirun =
      "ASAN_OPTIONS=detect_leaks=0 " + std::string(PROXIMA_MPIEXEC) + " --oversubscribe --allow-run-as-root -np ";
  sweep("split.json", "np1", mpirun + "1 ");
  sweep("split.json", "np3", mpirun + "3 ");
  for (const char* out : {"np1", "np3"}) {
    expect_same_items(dir.path / "whole", "i000_cluster_reflect", dir.path / out, "i003_cluster_reflect");
    expect_same_items(dir.path / "whole", "i001_visibility", dir.path / out, "i007_visibility");
    const Results r = read_results_json(dir.path / out / "results.json");
    EXPECT_GT(expect_same_metrics(merged, r), 30u) << out;
    expect_same_images(merged, r, dir.path / "local", dir.path / out);
  }
#endif
}

}  // namespace
}  // namespace proxima
