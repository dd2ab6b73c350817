// study/technique_bench.h: the ratio table, the crossover column and the error-vs-ms curves
// follow from the points; the points follow from each study's metrics; bad flags are named;
// one real run (visibility) gives a finite, honest point; a real cluster run with SSR gives
// SSR's point beside the cluster method's.
#include "proxima/study/technique_bench.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <variant>

#include "proxima/core/error.h"
#include "proxima/scene/load.h"
#include "proxima/study/cluster_reflect.h"
#include "study_test_util.h"
#include "test_util.h"

namespace proxima {
namespace {

using study::TechniquePoint;

const Table& table_starting(const Results& r, const std::string& prefix) {
  for (const Table& t : r.tables)
    if (t.title.rfind(prefix, 0) == 0) return t;
  ADD_FAILURE() << "no table " << prefix;
  static const Table none;
  return none;
}

size_t column(const Table& t, const std::string& name) {
  for (size_t i = 0; i < t.columns.size(); ++i)
    if (t.columns[i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

TEST(TechniqueBench, EnvmapPointsComeFromTheStudysMetrics) {
  const std::map<std::string, double> m = {
      {"reference_ms", 300},        {"envmap_ms", 10},        {"envmap_with_build_ms", 610}, {"envmap_mae", 20},
      {"rectified_ms", 20},         {"rectified_with_build_ms", 620}, {"rectified_mae", 1},
      {"average_ms", 12},           {"average_with_build_ms", 615},   {"average_mae", 11},
      {"layered_ms", 600},          {"layered_with_build_ms", 1400},  {"layered_mae", 0.5},
      {"boxprobe_ms", 9},           {"boxprobe_with_build_ms", 609},  {"boxprobe_mae", 1.3}};
  const auto points = study::technique_points("envmap", "room-reflector", "cube size", 256, true,
                                              [&](const std::string& n) { return m.at(n); });
  ASSERT_EQ(points.size(), 5u);
  EXPECT_EQ(points[1].method, "rectified");
  EXPECT_EQ(points[1].ms, 20);
  EXPECT_EQ(points[1].reference_ms, 300);
  EXPECT_EQ(points[1].approximation_build_ms, 600);
  EXPECT_EQ(points[1].error, 1);
  EXPECT_EQ(points[3].approximation_build_ms, 800);
  EXPECT_EQ(points[4].method, "boxprobe");
  EXPECT_EQ(points[4].error, 1.3);
}

TEST(TechniqueBench, RatiosAndTheSettingsThatBeatEmbree) {
  auto pt = [](const char* method, double knob, bool demo, double ms, double ref, double err) {
    TechniquePoint p;
    p.technique = "cluster";
    p.method = method;
    p.knob = "resolution scale";
    p.knob_value = knob;
    p.demo = demo;
    p.ms = ms;
    p.reference_ms = ref;
    p.reference_build_ms = 50;
    p.error = err;
    p.error_unit = "MAE 0–255";
    return p;
  };
  // living-room: slower than Embree at the demo's scale 1, faster at 0.5; bathroom: faster.
  const std::vector<TechniquePoint> points = {pt("living-room walk", 1, true, 400, 100, 1.5),
                                              pt("living-room walk", 0.5, false, 80, 100, 3),
                                              pt("living-room walk", 2, false, 900, 100, 1),
                                              pt("bathroom walk", 1, true, 500, 1000, 0.2)};
  const Results r = study::technique_bench_results(points);
  const Table& t = table_starting(r, "Techniques vs Embree");
  ASSERT_EQ(t.rows.size(), 2u);  // the demo points only
  EXPECT_DOUBLE_EQ(std::get<double>(t.rows[0][column(t, "ratio")]), 0.25);
  EXPECT_DOUBLE_EQ(std::get<double>(t.rows[0][column(t, "ratio with preparation")]), 150.0 / 400.0);
  EXPECT_EQ(std::get<std::string>(t.rows[0][column(t, "faster than Embree at")]), "resolution scale 0.5");
  EXPECT_EQ(std::get<std::string>(t.rows[1][column(t, "faster than Embree at")]), "the demo's setting");
  EXPECT_DOUBLE_EQ(r.metrics.at("cluster_living-room_walk_ratio"), 0.25);
  EXPECT_DOUBLE_EQ(r.metrics.at("cluster_bathroom_walk_ratio"), 2.0);

  // The curve: each method's points in ms order, then Embree's two times at error 0.
  const Table& c = table_starting(r, "Error vs ms: cluster");
  ASSERT_EQ(c.rows.size(), 6u);
  const size_t ms = column(c, "ms"), lr = column(c, "living-room walk"), emb = column(c, "Embree");
  EXPECT_EQ(std::get<double>(c.rows[0][ms]), 80);
  EXPECT_EQ(std::get<double>(c.rows[0][lr]), 3);
  EXPECT_EQ(std::get<double>(c.rows[2][ms]), 900);
  EXPECT_TRUE(std::isnan(std::get<double>(c.rows[0][emb])));
  EXPECT_EQ(std::get<double>(c.rows[4][ms]), 100);
  EXPECT_EQ(std::get<double>(c.rows[5][ms]), 1000);
  EXPECT_EQ(std::get<double>(c.rows[5][emb]), 0);
  ASSERT_EQ(r.sections.size(), 1u);
  ASSERT_EQ(r.sections[0].plots.size(), 1u);
  EXPECT_EQ(r.sections[0].plots[0].table, c.title);
}

// A tiny cluster run with ssr: SSR's point carries the study's SSR error and frame time, Embree the
// cluster point's, and the fallback's cube-map build as preparation; without ssr, no point.
TEST(TechniqueBench, ClusterRunWithSsrGivesAnSsrPoint) {
  const Scene scene = load_scene("room-reflector");
  study::ClusterReflectOptions o = tiny_cluster_options();
  o.ssr = true;
  const std::map<std::string, double> m = study::run_cluster_reflect(scene, o, {}).metrics;
  auto get = [&](const std::string& n) { return m.count(n) ? m.at(n) : std::nan(""); };
  const auto points = study::technique_points("cluster", "room-reflector", "resolution scale", 1, true, get);
  ASSERT_EQ(points.size(), 2u);
  const TechniquePoint& cluster = points[0];
  const TechniquePoint& ssr = points[1];
  EXPECT_EQ(cluster.method, "room-reflector");
  EXPECT_EQ(ssr.method, "ssr room-reflector");
  EXPECT_EQ(ssr.knob, "max steps");
  EXPECT_EQ(ssr.knob_value, SsrOptions{}.max_steps);
  EXPECT_TRUE(std::isfinite(ssr.error));
  EXPECT_GT(ssr.error, 0);
  EXPECT_EQ(ssr.error, (m.at("ssr_mae_r") + m.at("ssr_mae_g") + m.at("ssr_mae_b")) / 3.0);
  EXPECT_NE(ssr.error, cluster.error);
  EXPECT_TRUE(std::isfinite(ssr.ms));
  // The frame time holds the depth passes and the walk (with shading and fallback lookups).
  EXPECT_GE(ssr.ms, m.at("ssr_depth_passes_ms_avg") + m.at("ssr_trace_ms_avg"));
  EXPECT_GT(ssr.ms, 0);
  EXPECT_EQ(ssr.reference_ms, cluster.reference_ms);
  EXPECT_EQ(ssr.reference_build_ms, cluster.reference_build_ms);
  EXPECT_EQ(ssr.approximation_build_ms, m.at("envmap_build_ms_avg"));
  EXPECT_GT(ssr.approximation_build_ms, 0);

  const Results r = study::technique_bench_results(points);
  EXPECT_EQ(r.metrics.at("cluster_ssr_room-reflector_error"), ssr.error);
  EXPECT_EQ(r.metrics.at("cluster_ssr_room-reflector_ms"), ssr.ms);
  EXPECT_EQ(table_starting(r, "Techniques vs Embree").rows.size(), 2u);
  const Table& c = table_starting(r, "Error vs ms: cluster");
  const size_t col = column(c, "ssr room-reflector");
  size_t with_ssr = 0;
  for (const auto& row : c.rows)
    if (!std::isnan(std::get<double>(row[col]))) {
      ++with_ssr;
      EXPECT_EQ(std::get<double>(row[col]), ssr.error);
      EXPECT_EQ(std::get<std::string>(row[1]), "max steps 256 (demo)");
    }
  EXPECT_EQ(with_ssr, 1u);

  o.ssr = false;
  const std::map<std::string, double> plain = study::run_cluster_reflect(scene, o, {}).metrics;
  EXPECT_EQ(study::technique_points("cluster", "room-reflector", "resolution scale", 1, true,
                                    [&](const std::string& n) { return plain.count(n) ? plain.at(n) : std::nan(""); })
                .size(),
            1u);
}

TEST(TechniqueBench, BadFlagsAreNamed) {
  study::TechniqueBenchOptions o;
  o.techniques = "envmap,nope";
  EXPECT_NE(error_of([&] { study::validate(o); }).find("--techniques"), std::string::npos);
  o.techniques = "envmap";
  o.reps = 0;
  EXPECT_NE(error_of([&] { study::validate(o); }).find("--reps"), std::string::npos);
}

// The cheapest technique for real: the exact map beside Embree's item buffers of the same
// viewpoints, a finite time on both sides and an error that is a percentage.
TEST(TechniqueBench, VisibilityRunGivesAFinitePoint) {
  study::TechniqueBenchOptions o;
  o.techniques = "visibility";
  o.reps = 1;
  o.sweep = false;
  const auto points = study::measure_techniques(o, true);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_TRUE(points[0].demo);
  EXPECT_GT(points[0].ms, 0);
  EXPECT_GT(points[0].reference_ms, 0);
  EXPECT_GT(points[0].reference_build_ms, 0);
  EXPECT_GE(points[0].error, 0);
  EXPECT_LT(points[0].error, 5);  // the map agrees with Embree on almost every pixel
}

}  // namespace
}  // namespace proxima
