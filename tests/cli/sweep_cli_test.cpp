// `proxima sweep`: under `mpirun -np 3` a small manifest (two scenes, four studies, a
// parameter grid, a GIBR run split into per-photograph items, and one bad item) gives the
// same deterministic metrics and image bits as `-np 1` and as the in-process run, the bad item recorded and the others
// finished; a sweep killed half-way resumes without redoing finished items; a bad manifest
// writes nothing.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <map>
#include <string>
#include <thread>

#include "cli/cli_util.h"
#include "proxima/eval/results.h"
#include "study/study_test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

constexpr const char* kManifest = R"({"runs": [
  {"study": "reference", "scene": ["cornell", "room-reflector"],
   "options": {"width": 32, "height": 24, "light_samples": 1}},
  {"study": "envmap_reflect", "scene": "room-reflector",
   "options": {"width": 32, "height": 24, "light_samples": 1, "reps": 1, "compare": true},
   "grid": {"cube_size": [16, 32]}},
  {"study": "sampling", "scene": "cornell", "options": {"width": 32, "frames": 8, "reps": 1}},
  {"study": "gibr", "scene": "rooms",
   "options": {"photos": 3, "photo_width": 32, "photo_height": 24, "supersample": 1,
               "width": 32, "height": 24, "frames": 1, "fps_repeat": 1}},
  {"study": "reference", "scene": "no-such-scene.json"}
]})";

size_t finished_items(const fs::path& out) {
  size_t n = 0;
  if (fs::exists(out / "items"))
    for (const auto& e : fs::directory_iterator(out / "items"))  // not the .<id>.tmp being written
      n += e.path().filename().string()[0] != '.' && fs::exists(e.path() / "item.json");
  return n;
}

void expect_same_sweep(const fs::path& a, const fs::path& b) {
  const Results ra = read_results_json(a / "results.json");
  const Results rb = read_results_json(b / "results.json");
  EXPECT_GT(expect_same_metrics(ra, rb), 30u);
  EXPECT_GT(expect_same_metrics(rb, ra), 30u);
  expect_same_images(ra, rb, a, b);
  EXPECT_GT(ra.images.size(), 10u);
}

TEST(SweepCli, RanksGiveTheInProcessResultsAndABadItemFailsAlone) {
#ifndef PROXIMA_MPIEXEC
  GTEST_SKIP() << "built without MPI (PROXIMA_MPI): only the in-process sweep";
#else
  TempDir dir;
  write_file(dir.path / "m.json", kManifest);
  const std::string args = "sweep " + (dir.path / "m.json").string() + " --threads 1 --out ";
  const RunResult local = run_cli(args + (dir.path / "local").string());
  const std::string mpirun = std::string(PROXIMA_MPIEXEC) + " --oversubscribe --allow-run-as-root -np ";
  const RunResult one = run_cli(args + (dir.path / "np1").string(), mpirun + "1 ");
  const RunResult three = run_cli(args + (dir.path / "np3").string(), mpirun + "3 ");
  for (const RunResult* r : {&local, &one, &three}) {
    EXPECT_EQ(r->exit_code, 1) << r->output;  // one item failed
    EXPECT_NE(r->output.find("no-such-scene.json"), std::string::npos) << r->output;
  }
  EXPECT_NE(three.output.find("3 ranks"), std::string::npos) << three.output;
  const Results r = read_results_json(dir.path / "np3" / "results.json");
  EXPECT_EQ(r.metrics.at("sweep_items"), 10.0);  // the GIBR run: 3 photograph items and its own
  EXPECT_EQ(r.metrics.at("sweep_failed"), 1.0);
  EXPECT_TRUE(r.metrics.contains("i008_gibr_psnr_vismap"));
  expect_same_sweep(dir.path / "local", dir.path / "np1");
  expect_same_sweep(dir.path / "local", dir.path / "np3");
#endif
}

// Kills an in-process sweep after its first items, reruns it: the finished items keep
// their files (same modification times), the rest run, and every item ends ok.
TEST(SweepCli, KilledSweepResumesWithoutRedoingFinishedItems) {
  TempDir dir;
  write_file(dir.path / "m.json", R"({"runs": [{"study": "reference", "scene": "cornell",
      "options": {"width": 96, "height": 64, "spp": 2}, "grid": {"seed": [1, 2, 3, 4, 5, 6, 7, 8]}}]})");
  const fs::path out = dir.path / "out";
  const pid_t pid = fork();
  if (pid == 0) {
    execl(PROXIMA_CLI_PATH, PROXIMA_CLI_PATH, "sweep", (dir.path / "m.json").c_str(), "--threads", "1", "--out",
          out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (finished_items(out) < 2 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  const size_t before = finished_items(out);
  ASSERT_GE(before, 2u);
  std::map<std::string, fs::file_time_type> times;
  for (const auto& e : fs::directory_iterator(out / "items"))
    if (e.path().filename().string()[0] != '.' && fs::exists(e.path() / "item.json")) times[e.path().filename()] = fs::last_write_time(e.path() / "item.json");
  const RunResult rerun = run_cli("sweep " + (dir.path / "m.json").string() + " --threads 1 --out " + out.string());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_NE(rerun.output.find(std::to_string(before) + " already finished"), std::string::npos) << rerun.output;
  for (const auto& [id, t] : times) EXPECT_EQ(fs::last_write_time(out / "items" / id / "item.json"), t) << id;
  EXPECT_EQ(finished_items(out), 8u);
  EXPECT_EQ(read_results_json(out / "results.json").metrics.at("sweep_failed"), 0.0);
}

TEST(SweepCli, BadManifestExitsTwoWritingNothing) {
  TempDir dir;
  write_file(dir.path / "m.json", R"({"runs": [{"study": "reference", "scene": "cornell", "options": {"spq": 1}}]})");
  const RunResult r = run_cli("sweep " + (dir.path / "m.json").string() + " --out " + (dir.path / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'spq'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path / "out"));
}

}  // namespace
}  // namespace proxima
