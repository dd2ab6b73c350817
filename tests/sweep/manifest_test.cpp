// sweep/manifest.h: runs expand scene by scene over the grid's cartesian product in a fixed
// order, grid values override options, files resolve against the manifest's directory, and
// malformed manifests are refused naming the file, the run and the option.
#include "proxima/sweep/manifest.h"

#include <gtest/gtest.h>

#include <string>

#include "proxima/core/error.h"
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
      {R"({"runs": [{"study": "reference", "scene": "cornell", "frame_items": 2}]})", "does not split"},
      {R"({"runs": [{"study": "visibility", "scene": "rooms", "frame_items": 0}]})", "\"frame_items\""},
      {R"({"runs": [{"study": "visibility", "scene": "rooms", "frame_items": 1e300}]})", "\"frame_items\""},
      {R"({"runs": [{"study": "visibility", "scene": "rooms", "frame_items": 20000}]})", "1..10000"},
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

namespace proxima::sweep {
namespace {

// The full demo as a manifest: one item per study run of the demo (its planned runs, each
// through the catalog) plus one per GIBR photograph; every run directory maps to its item.
TEST(SweepManifest, DemoManifestHasAnItemPerStudyRunOfTheDemo) {
  study::DemoOptions full;
  full.full = true;
  const std::vector<study::DemoStudyRun> plan = study::plan_demo(full);
  const Manifest m = parse_manifest(R"({"demo": {"full": true}})", ".", "full.json");
  ASSERT_TRUE(m.demo.has_value());
  EXPECT_TRUE(m.demo->full);
  ASSERT_EQ(m.demo_items.size(), plan.size());
  size_t photos = 0, parts = 0;
  for (const SweepItem& item : m.items) {
    photos += item.photo >= 0;
    parts += item.frame_part >= 0;
  }
  EXPECT_EQ(photos, 100u);  // the full GIBR run's photographs
  // Four cluster runs of 10 frames (900 / 90) and ten visibility runs: kDemoFrameItems parts each.
  EXPECT_EQ(parts, 14u * size_t(kDemoFrameItems));
  EXPECT_EQ(m.items.size(), plan.size() + photos + parts);
  for (const study::DemoStudyRun& run : plan) {
    ASSERT_TRUE(m.demo_items.contains(run.dir)) << run.dir;
    const SweepItem& item = m.items[m.demo_items.at(run.dir)];
    EXPECT_EQ(item.photo, -1);
    EXPECT_EQ(item.frame_part, -1);
    EXPECT_EQ(item.inputs.size(), item.frame_parts > 1 ? size_t(item.frame_parts) : item.inputs.size()) << run.dir;
    const study::CatalogRun c = study::catalog_run_from_command(run.args);
    EXPECT_EQ(item.study, c.study) << run.dir;
    EXPECT_EQ(item.options, c.options) << run.dir;
  }
  const SweepItem& gibr = m.items[m.demo_items.at("gibr/rooms")];
  EXPECT_EQ(gibr.inputs.size(), 100u);
  EXPECT_EQ(std::get<std::int64_t>(gibr.options.at("photo_width")), 320);
  // The quick demo has fewer or smaller runs: the settings come from the sections.
  const Manifest quick = parse_manifest(R"({"demo": {"only": ["gibr", "sampling"]}})", ".", "quick.json");
  EXPECT_EQ(std::get<std::int64_t>(quick.items[quick.demo_items.at("sampling/nest")].options.at("frames")), 100);
  EXPECT_EQ(std::get<std::int64_t>(m.items[m.demo_items.at("sampling/nest")].options.at("frames")), 1000);
}

TEST(SweepManifest, DemoManifestTextListsItsItemsAndAStaleListIsRefused) {
  study::DemoOptions o;
  o.only = {"gibr"};
  const std::string text = demo_manifest_json(o);
  const Manifest m = parse_manifest(text, ".", "demo.json");
  EXPECT_EQ(m.items.size(), 17u);  // 16 photographs and the run
  std::string stale = text;
  stale.replace(stale.find("\"rooms\""), 7, "\"floor\"");
  EXPECT_THROW(parse_manifest(stale, ".", "demo.json"), InputError);
  EXPECT_THROW(parse_manifest(R"({"demo": {"only": ["nope"]}})", ".", "d.json"), InputError);
  EXPECT_THROW(parse_manifest(R"({"demo": {"fulll": true}})", ".", "d.json"), InputError);
  EXPECT_THROW(parse_manifest(R"({"demo": {}, "runs": []})", ".", "d.json"), InputError);
}

// Commands map to catalog runs: the study, the scene, flags by name, the commands' own
// defaults (sample --height = --width, --gloss-rays, --no-*, visibility --floors).
TEST(SweepManifest, CommandsMapToCatalogRuns) {
  const study::CatalogRun s = study::catalog_run_from_command({"sample", "--scene", "nest", "--width", "64",
                                                               "--method", "conventional,peeling", "--out", "x"});
  EXPECT_EQ(s.study, "sampling");
  EXPECT_EQ(s.scene, "nest");
  EXPECT_EQ(std::get<std::int64_t>(s.options.at("height")), 64);
  EXPECT_EQ(std::get<std::string>(s.options.at("method")), "conventional,peeling");
  EXPECT_FALSE(s.options.contains("out"));
  const study::CatalogRun t = study::catalog_run_from_command(
      {"reflect", "--method", "cluster", "--scene", "bathroom", "--gloss-rays", "8", "--compare"});
  EXPECT_EQ(t.study, "cluster_reflect");
  EXPECT_EQ(std::get<std::int64_t>(t.options.at("glossy_rays")), 8);
  EXPECT_TRUE(std::get<bool>(t.options.at("compare")));
  EXPECT_FALSE(t.options.contains("method"));
  EXPECT_FALSE(t.options.contains("ssr"));
  const study::CatalogRun ssr = study::catalog_run_from_command({"reflect", "--method", "ssr", "--scene", "bathroom"});
  EXPECT_EQ(ssr.study, "cluster_reflect");
  EXPECT_TRUE(std::get<bool>(ssr.options.at("ssr")));
  const study::CatalogRun v =
      study::catalog_run_from_command({"visibility", "--scene", "building", "--floors", "3", "--no-oracle"});
  EXPECT_EQ(v.scene, "building:floors=3");
  EXPECT_FALSE(std::get<bool>(v.options.at("oracle")));
  EXPECT_EQ(study::catalog_run_from_command({"reflect", "--cube-size", "64"}).study, "envmap_reflect");
  EXPECT_THROW(study::catalog_run_from_command({"reflect", "--no-such-flag", "1"}), InputError);
  EXPECT_THROW(study::catalog_run_from_command({"sample", "--width", "wide"}), InputError);
  EXPECT_THROW(study::catalog_run_from_command({"view"}), InputError);
}

}  // namespace
}  // namespace proxima::sweep
