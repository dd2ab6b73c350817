// `proxima results merge|page` end to end: bad input exits 2 naming the file or run and
// writes nothing; a merge then a page writes both, and a page whose input lacks metrics
// exits 3 naming them.
#include <gtest/gtest.h>

#include "cli/cli_util.h"
#include "proxima/eval/results.h"

namespace proxima {
namespace {

void write_run(const std::filesystem::path& path, const std::string& commit) {
  Results r;
  r.command = {"proxima", "bench", "trace"};
  r.threads = 2;
  r.build = "Release";
  r.commit = commit;
  r.cpu = "test cpu";
  r.metrics = {{"primary_mrays_s", 7.5}};
  write_results_json(path, r);
}

TEST(ResultsCli, BadInputExitsTwoNamingTheFileOrRunAndWritesNothing) {
  TempDir dir;
  const std::string out = (dir.path / "merged.json").string();
  RunResult r = run_cli("results merge demo=" + (dir.path / "missing.json").string() + " --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("missing.json: cannot open"), std::string::npos) << r.output;
  r = run_cli("results merge demo --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'demo' is not NAME=RESULTS_JSON"), std::string::npos) << r.output;
  write_run(dir.path / "a.json", "abc");
  write_run(dir.path / "b.json", "def");
  r = run_cli("results merge a=" + (dir.path / "a.json").string() + " b=" + (dir.path / "b.json").string() +
              " --out " + out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("run 'b': commit 'def'"), std::string::npos) << r.output;
  write_file(dir.path / "bad.json", "{\"command\": [");
  r = run_cli("results page " + (dir.path / "bad.json").string() + " --out " + (dir.path / "page.md").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.json: malformed results.json"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(dir.path / "page.md"));
}

TEST(ResultsCli, MergeThenPageWritesBothAndNamesMissingMetrics) {
  TempDir dir;
  write_run(dir.path / "trace.json", "abc");
  const std::string merged = (dir.path / "merged.json").string(), page = (dir.path / "page.md").string();
  RunResult r = run_cli("results merge bench_trace=" + (dir.path / "trace.json").string() + " --out " + merged);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_results_json(merged).metrics.at("bench_trace_primary_mrays_s"), 7.5);
  r = run_cli("results page " + merged + " --out " + page);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("lacks metric demo_id_agreement_pct"), std::string::npos) << r.output;
  ASSERT_TRUE(std::filesystem::exists(page));
  std::ifstream in(page);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(text.find("7.50 Mrays/s primary"), std::string::npos);
}

}  // namespace
}  // namespace proxima
