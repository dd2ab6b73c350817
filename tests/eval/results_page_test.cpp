// docs/RESULTS.md as a generated page: the committed page is what docs/results.json gives
// byte for byte; merging keeps every run's figures apart and refuses mixed provenance.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "proxima/eval/results_merge.h"
#include "proxima/eval/results_page.h"
#include "test_util.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

// The docs/ folder of the source tree the tested binary was configured from (the
// CMakeCache.txt beside it names that tree; __FILE__ may be relative or another tree's
// under a shared compiler cache).
fs::path docs_dir() {
  const std::string key = "CMAKE_HOME_DIRECTORY:INTERNAL=";
  std::ifstream in(fs::path(PROXIMA_CLI_PATH).parent_path() / "CMakeCache.txt");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key, 0) == 0) return fs::path(line.substr(key.size())) / "docs";
  return {};
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Results run(const std::string& commit, int threads, std::map<std::string, double> metrics) {
  Results r;
  r.command = {"proxima", "bench", "trace"};
  r.threads = threads;
  r.build = "Release";
  r.commit = commit;
  r.cpu = "test cpu";
  r.metrics = std::move(metrics);
  r.tables.push_back({"speed", {"threads", "ms"}, {{1.0, 2.5}}});
  r.sections.push_back({"trace", "Trace", "", {"speed"}, {"image role"}, {"proxima bench trace --out x"}});
  return r;
}

TEST(ResultsPage, CommittedPageIsRegeneratedByteForByte) {
  const fs::path json = docs_dir() / "results.json", page_path = docs_dir() / "RESULTS.md";
  ASSERT_TRUE(fs::exists(json)) << json << " (source tree from the CMakeCache.txt beside " << PROXIMA_CLI_PATH << ")";
  const ResultsPage page = results_page(read_results_json(json));
  EXPECT_TRUE(page.missing.empty()) << "docs/results.json lacks " << page.missing.front();
  EXPECT_EQ(page.markdown, read_text(page_path))
      << "docs/RESULTS.md is not what docs/results.json gives: run `build/release/proxima results page "
         "docs/results.json --out docs/RESULTS.md` (or scripts/results.sh)";
  EXPECT_LE(std::count(page.markdown.begin(), page.markdown.end(), '\n'), 300);
}

TEST(ResultsPage, SameBytesAfterAJsonRoundTrip) {
  const Results merged = merge_results({{"demo", run("abc", 2, {{"demo_seconds", 61.0 / 3.0}})},
                                        {"bench_trace", run("abc", 2, {{"primary_mrays_s", 1.0 / 7.0}})}},
                                       {"proxima", "results", "merge"});
  TempDir dir;
  write_results_json(dir.path / "results.json", merged);
  const ResultsPage direct = results_page(merged);
  const ResultsPage reread = results_page(read_results_json(dir.path / "results.json"));
  EXPECT_EQ(direct.markdown, reread.markdown);
  EXPECT_EQ(direct.missing, reread.missing);
}

TEST(ResultsPage, MissingMetricsAreListedAndShownAsDashes) {
  const Results merged = merge_results({{"demo", run("abc", 2, {{"demo_seconds", 59.0}})}}, {"proxima"});
  const ResultsPage page = results_page(merged);
  EXPECT_FALSE(page.missing.empty());
  EXPECT_NE(std::find(page.missing.begin(), page.missing.end(), "bench_trace_primary_mrays_s"), page.missing.end());
  EXPECT_EQ(std::find(page.missing.begin(), page.missing.end(), "demo_demo_seconds"), page.missing.end());
  EXPECT_NE(page.markdown.find("The demo took 59 s."), std::string::npos);
  EXPECT_NE(page.markdown.find("| — |"), std::string::npos);
}

// The demo's techniques-vs-Embree table is shown when the demo wrote one, and only then.
TEST(ResultsPage, TechniquesVsEmbreeTableWhenTheDemoHasIt) {
  Results demo = run("abc", 2, {{"demo_seconds", 59.0}});
  const std::string without = results_page(merge_results({{"demo", demo}}, {"proxima"})).markdown;
  EXPECT_EQ(without.find("## Techniques vs Embree"), std::string::npos);
  demo.tables.push_back({"Techniques vs Embree at the demo's settings (ratio)", {"technique", "ratio"},
                         {{std::string("cluster"), 0.41}}});
  const std::string with = results_page(merge_results({{"demo", demo}}, {"proxima"})).markdown;
  EXPECT_NE(with.find("## Techniques vs Embree"), std::string::npos);
  EXPECT_NE(with.find("| cluster | 0.41 |"), std::string::npos);
}

TEST(ResultsMerge, PrefixesEveryRunsFiguresAndKeepsItsCommand) {
  const Results merged = merge_results({{"demo", run("abc", 2, {{"x_ms", 1.0}})},
                                        {"bench_trace", run("abc", 2, {{"x_ms", 2.0}})}},
                                       {"proxima", "results", "merge"});
  EXPECT_EQ(merged.metrics.at("demo_x_ms"), 1.0);
  EXPECT_EQ(merged.metrics.at("bench_trace_x_ms"), 2.0);
  EXPECT_EQ(merged.metrics.size(), 2u);
  EXPECT_EQ(merged.commit, "abc");
  EXPECT_EQ(merged.threads, 2);
  ASSERT_EQ(merged.tables.size(), 2u);
  EXPECT_EQ(merged.tables[1].title, "bench_trace: speed");
  ASSERT_EQ(merged.sections.size(), 4u);
  EXPECT_EQ(merged.sections[2].id, "bench_trace");
  EXPECT_EQ(merged.sections[2].commands, std::vector<std::string>{"proxima bench trace"});
  EXPECT_EQ(merged.sections[3].id, "bench_trace-trace");
  EXPECT_EQ(merged.sections[3].tables, std::vector<std::string>{"bench_trace: speed"});
  EXPECT_TRUE(merged.sections[3].images.empty());
  EXPECT_TRUE(merged.images.empty());
}

TEST(ResultsMerge, RefusesMixedProvenanceAndBadNames) {
  const Results a = run("abc", 2, {}), b = run("def", 2, {}), c = run("abc", 1, {});
  EXPECT_NE(error_of([&] { merge_results({{"demo", a}, {"trace", b}}, {}); }).find("commit 'def'"),
            std::string::npos);
  EXPECT_NE(error_of([&] { merge_results({{"demo", a}, {"trace", c}}, {}); }).find("threads '1'"), std::string::npos);
  EXPECT_NE(error_of([&] { merge_results({{"demo", a}, {"demo", a}}, {}); }).find("given twice"), std::string::npos);
  EXPECT_NE(error_of([&] { merge_results({{"Demo", a}}, {}); }).find("run name 'Demo'"), std::string::npos);
  EXPECT_NE(error_of([&] { merge_results({}, {}); }).find("no runs"), std::string::npos);
  // "a_b" + "c" and "a" + "b_c" would both be "a_b_c".
  EXPECT_NE(error_of([&] {
              merge_results({{"a_b", run("abc", 2, {{"c", 1.0}})}, {"a", run("abc", 2, {{"b_c", 2.0}})}}, {});
            }).find("already another run's"),
            std::string::npos);
}

}  // namespace
}  // namespace proxima
