// sweep/manifest.h: runs expand scene by scene over the grid's cartesian product in a fixed
// order, grid values override options, files resolve against the manifest's directory, and
// malformed manifests are refused naming the file, the run and the option.
#include "proxima/sweep/manifest.h"

#include <gtest/gtest.h>

#include <string>

#include "test_util.h"

namespace proxima::sweep {
namespace {

TEST(SweepManifest, ExpandsScenesOuterGridInnerLastKeyFastest) {
  const Manifest m = parse_manifest(R"({"runs": [
      {"study": "envmap_reflect", "scene": ["cornell", "models/a.obj"],
       "options": {"width": 32, "d_e": 0.5}, "grid": {"d_e": [0.01, 0.02], "cube_size": [16, 32]}},
      {"study": "reference", "scene": "/abs/b.json"}]})",
                                    "/data/sweeps", "m.json");
  ASSERT_EQ(m.items.size(), 9u);
  EXPECT_EQ(m.items[0].id, "i000_envmap_reflect");
  EXPECT_EQ(m.items[8].id, "i008_reference");
  EXPECT_EQ(m.items[0].scene, "cornell");
  EXPECT_EQ(m.items[4].scene, "/data/sweeps/models/a.obj");
  EXPECT_EQ(m.items[8].scene, "/abs/b.json");
  // Keys in name order: cube_size, then d_e fastest; the grid's d_e overrides the option's.
  const std::vector<std::pair<std::int64_t, double>> expected = {{16, 0.01}, {16, 0.02}, {32, 0.01}, {32, 0.02}};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(std::get<std::int64_t>(m.items[i].options.at("cube_size")), expected[i].first) << i;
    EXPECT_EQ(std::get<double>(m.items[i].options.at("d_e")), expected[i].second) << i;
    EXPECT_EQ(std::get<std::int64_t>(m.items[i].options.at("width")), 32) << i;
    EXPECT_EQ(m.items[i + 4].options, m.items[i].options) << i;
  }
  EXPECT_TRUE(m.items[8].options.empty());
}

TEST(SweepManifest, MalformedManifestsAreRefusedNamingWhere) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{", "not valid JSON"},
      {R"({"runs": []})", "at least one run"},
      {R"({"runs": [{"scene": "cornell"}]})", "runs[0]: \"study\" missing"},
      {R"({"runs": [{"study": "reference"}]})", "\"scene\" missing"},
      {R"({"runs": [{"study": "renderer", "scene": "cornell"}]})", "'renderer'"},
      {R"({"runs": [{"study": "reference", "scene": "cornell", "options": {"spq": 2}}]})", "'spq'"},
      {R"({"runs": [{"study": "reference", "scene": "cornell", "options": {"spp": "2"}}]})", "'spp'"},
      {R"({"runs": [{"study": "reference", "scene": "cornell", "options": {"spp": [2]}}]})", "option \"spp\""},
      {R"({"runs": [{"study": "reference", "scene": "cornell", "grid": {"spp": []}}]})", "grid \"spp\""},
      {R"({"runs": [{"study": "reference", "scene": "cornell", "grid": {"spp": [1, "x"]}}]})", "'spp'"},
      {R"({"runs": [{"study": "reference", "scene": "cornell", "frames": 3}]})", "unknown key \"frames\""},
      {R"({"runs": [{"study": "reference", "scene": []}]})", "\"scene\""},
  };
  for (const auto& [text, part] : cases) {
    const std::string e = error_of([&] { parse_manifest(text, ".", "m.json"); });
    EXPECT_NE(e.find("m.json"), std::string::npos) << text << " → " << e;
    EXPECT_NE(e.find(part), std::string::npos) << text << " → " << e;
  }
  EXPECT_NE(error_of([] { read_manifest("/nonexistent/m.json"); }).find("/nonexistent/m.json"), std::string::npos);
}

}  // namespace
}  // namespace proxima::sweep
