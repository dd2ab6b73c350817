// study/catalog.h: every study is reachable by name, the catalog's defaults are the options
// structs' defaults, each option sets its own member, a run through the catalog equals the
// direct call, and unknown or mistyped options are refused naming them.
#include "proxima/study/catalog.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/study/cluster_reflect.h"
#include "proxima/study/envmap_reflect.h"
#include "proxima/study/gibr.h"
#include "proxima/study/sampling.h"
#include "proxima/study/shadows.h"
#include "proxima/study/temporal_reflect.h"
#include "proxima/study/visibility.h"
#include "study_test_util.h"
#include "test_util.h"

namespace proxima {
namespace {

using study::OptionValue;
using study::OptionValues;

const study::OptionInfo& option(const std::string& study_name, const std::string& name) {
  for (const study::OptionInfo& o : study::study_info(study_name).options)
    if (o.name == name) return o;
  ADD_FAILURE() << study_name << " has no option " << name;
  static const study::OptionInfo none;
  return none;
}

TEST(StudyCatalog, ListsEveryStudyOfTheStudyHeaders) {
  std::vector<std::string> names;
  for (const study::StudyInfo& s : study::study_catalog()) {
    names.push_back(s.name);
    EXPECT_FALSE(s.summary.empty()) << s.name;
    EXPECT_FALSE(s.options.empty()) << s.name;
    for (const study::OptionInfo& o : s.options) EXPECT_FALSE(o.doc.empty()) << s.name << "." << o.name;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"cluster_reflect", "envmap_reflect", "gibr", "raster_bench", "reference",
                                             "sampling", "shadows", "technique_bench", "temporal_reflect", "trace_bench",
                                             "visibility"}));
}

// Each name reaches its own study: a value out of range is refused by that study's
// validate(), whose message names a flag only that study has.
TEST(StudyCatalog, EveryStudyIsReachableByName) {
  const Scene scene = make_builtin_scene("cornell");
  const std::vector<std::tuple<std::string, OptionValues, std::string>> cases = {
      {"cluster_reflect", {{"theta_bins", std::int64_t{0}}}, "--theta-bins"},
      {"envmap_reflect", {{"march_steps", std::int64_t{0}}}, "--march-steps"},
      {"gibr", {{"k", std::int64_t{0}}}, "--k"},
      {"reference", {{"bounces", std::int64_t{17}}}, "--bounces"},
      {"sampling", {{"radius", -1.0}}, "--radius"},
      {"shadows", {{"light_size", 0.0}}, "--light-size"},
      {"temporal_reflect", {{"path", std::string("0")}, {"threshold", 2.0}}, "--threshold"},
      {"visibility", {{"selfcheck_rays", std::int64_t{0}}}, "--selfcheck-rays"},
      {"technique_bench", {{"techniques", std::string("nope")}}, "--techniques"},
  };
  for (const auto& [name, values, flag] : cases)
    EXPECT_NE(error_of([&] { study::run_study(name, scene, values, {}); }).find(flag), std::string::npos) << name;
  // The two benchmarks share their flags: tiny runs, told apart by their metrics.
  const OptionValues tiny = {{"width", std::int64_t{8}}, {"height", std::int64_t{8}}, {"threads", std::int64_t{1}},
                             {"reps", std::int64_t{1}}};
  EXPECT_TRUE(study::run_study("trace_bench", scene, tiny, {}).metrics.contains("primary_mrays_s"));
  OptionValues raster = tiny;
  raster["skip_agreement"] = true;
  EXPECT_TRUE(study::run_study("raster_bench", scene, raster, {}).metrics.contains("raster_ms_depth_id"));
}

TEST(StudyCatalog, DefaultsAreTheOptionsStructs) {
  using study::option_text;
  EXPECT_EQ(option_text(option("envmap_reflect", "cube_size").default_value),
            std::to_string(study::EnvmapReflectOptions{}.cube_size));
  EXPECT_EQ(std::get<double>(option("envmap_reflect", "d_e").default_value), study::EnvmapReflectOptions{}.d_e);
  EXPECT_EQ(std::get<std::int64_t>(option("gibr", "photos").default_value), study::GibrOptions{}.model.photos);
  EXPECT_EQ(std::get<bool>(option("gibr", "unmix").default_value), study::GibrOptions{}.model.unmix);
  EXPECT_EQ(std::get<std::int64_t>(option("cluster_reflect", "ss").default_value),
            study::ClusterReflectOptions{}.reflection.supersample);
  EXPECT_EQ(std::get<std::int64_t>(option("cluster_reflect", "theta_bins").default_value),
            study::ClusterReflectOptions{}.cluster.clustering.max_theta_bins);
  EXPECT_EQ(std::get<double>(option("temporal_reflect", "threshold").default_value),
            study::TemporalReflectOptions{}.threshold);
  EXPECT_TRUE(std::isinf(std::get<double>(option("temporal_reflect", "spread_limit").default_value)));
  EXPECT_EQ(std::get<std::int64_t>(option("visibility", "selfcheck_rays").default_value),
            study::VisibilityOptions{}.selfcheck_rays);
  EXPECT_EQ(option_text(option("shadows", "sampling").default_value), "nrr");
  EXPECT_EQ(option_text(option("sampling", "method").default_value), "nrr-pixel");
  EXPECT_EQ(option_text(option("sampling", "redundancy").default_value), "");  // none: the study's rule
  EXPECT_EQ(option_text(option("gibr", "views").default_value), "path");
  // Resolving no options gives every default.
  for (const study::StudyInfo& s : study::study_catalog()) {
    const OptionValues all = study::resolved_options(s.name, {});
    ASSERT_EQ(all.size(), s.options.size()) << s.name;  // option names are unique
    for (const study::OptionInfo& o : s.options) EXPECT_EQ(all.at(o.name), o.default_value) << s.name << "." << o.name;
  }
}

// A value of the option's type that differs from its default.
OptionValue other_value(const study::OptionInfo& o) {
  if (const bool* b = std::get_if<bool>(&o.default_value)) return !*b;
  if (const std::int64_t* i = std::get_if<std::int64_t>(&o.default_value)) return *i + 1;
  if (const double* d = std::get_if<double>(&o.default_value)) return *d == 2.5 ? 3.5 : 2.5;  // exact in float
  for (const std::string& c : o.choices)
    if (OptionValue(c) != o.default_value) return c;
  return std::string("other");
}

// No two options set the same member, and each value comes back as given.
TEST(StudyCatalog, EachOptionSetsItsOwnMember) {
  for (const study::StudyInfo& s : study::study_catalog()) {
    const OptionValues defaults = study::resolved_options(s.name, {});
    for (const study::OptionInfo& o : s.options) {
      const OptionValue v = other_value(o);
      OptionValues expected = defaults;
      expected[o.name] = v;
      EXPECT_EQ(study::resolved_options(s.name, {{o.name, v}}), expected) << s.name << "." << o.name;
    }
  }
}

TEST(StudyCatalog, RunEqualsTheDirectCall) {
  const Scene scene = make_builtin_scene("room-reflector");
  study::EnvmapReflectOptions o;
  o.compare = true;
  o.width = 96;
  o.height = 72;
  o.cube_size = 64;
  o.light_samples = 1;
  o.reps = 1;
  const OptionValues values = {{"compare", true},          {"width", std::int64_t{96}},       {"height", std::int64_t{72}},
                               {"cube_size", std::int64_t{64}}, {"light_samples", std::int64_t{1}}, {"reps", std::int64_t{1}}};
  TempDir a, b;
  const Results direct = study::run_envmap_reflect(scene, o, {a.path});
  const Results catalog = study::run_study("envmap_reflect", scene, values, {b.path});
  EXPECT_GT(expect_same_metrics(direct, catalog), 20u);
  expect_same_images(direct, catalog, a.path, b.path);
}

// --frame runs that frame alone in the cluster study (the command line's frame_given).
TEST(StudyCatalog, ClusterFrameRunsThatFrameAlone) {
  const Scene scene = make_builtin_scene("room-reflector");
  study::ClusterReflectOptions o;
  o.width = 48;
  o.height = 32;
  o.camera.path = "0";
  o.camera.frame = 1;
  o.frame_given = true;
  o.reflection.supersample = 1;
  const OptionValues values = {{"width", std::int64_t{48}}, {"height", std::int64_t{32}}, {"path", std::string("0")},
                               {"frame", std::int64_t{1}},  {"ss", std::int64_t{1}}};
  const Results direct = study::run_cluster_reflect(scene, o, {});
  const Results catalog = study::run_study("cluster_reflect", scene, values, {});
  EXPECT_EQ(catalog.metrics.at("frames"), 1.0);
  EXPECT_GT(expect_same_metrics(direct, catalog), 5u);
}

TEST(StudyCatalog, BadOptionsAreRefusedNamingThem) {
  const Scene scene = make_builtin_scene("cornell");
  auto error = [&](const std::string& name, const OptionValues& values) {
    return error_of([&] { study::run_study(name, scene, values, {}); });
  };
  EXPECT_NE(error("envmap_reflekt", {}).find("envmap_reflekt"), std::string::npos);
  EXPECT_NE(error("envmap_reflect", {{"cube_sise", std::int64_t{64}}}).find("'cube_sise'"), std::string::npos);
  EXPECT_NE(error("envmap_reflect", {{"cube_size", std::string("big")}}).find("'cube_size'"), std::string::npos);
  EXPECT_NE(error("envmap_reflect", {{"cube_size", 64.0}}).find("'cube_size'"), std::string::npos);
  EXPECT_NE(error("envmap_reflect", {{"cube_size", std::int64_t{1} << 40}}).find("'cube_size'"), std::string::npos);
  EXPECT_NE(error("envmap_reflect", {{"compare", std::int64_t{1}}}).find("'compare'"), std::string::npos);
  EXPECT_NE(error("envmap_reflect", {{"d_e", std::string("small")}}).find("'d_e'"), std::string::npos);
  EXPECT_NE(error("envmap_reflect", {{"d_e", 1e300}}).find("'d_e'"), std::string::npos);
  EXPECT_NE(error("gibr", {{"views", std::string("sideways")}}).find("'views'"), std::string::npos);
  EXPECT_NE(error("gibr", {{"seed", std::int64_t{-1}}}).find("'seed'"), std::string::npos);
  EXPECT_NE(error("shadows", {{"sampling", std::string("nrr,bogus")}}).find("'sampling'"), std::string::npos);
  EXPECT_NE(error("envmap_reflect", {{"cube_size", std::int64_t{0}}}).find("--cube-size"), std::string::npos);
}

TEST(StudyCatalog, FloatOptionsTakeIntsAndInfinity) {
  const OptionValues r = study::resolved_options(
      "temporal_reflect", {{"spread_limit", std::string("inf")}, {"edge_contrast", std::int64_t{3}}});
  EXPECT_EQ(r.at("spread_limit"), OptionValue(std::numeric_limits<double>::infinity()));
  EXPECT_EQ(r.at("edge_contrast"), OptionValue(3.0));
  EXPECT_EQ(study::option_text(r.at("spread_limit")), "inf");
  EXPECT_EQ(study::option_text(OptionValue(0.1)), "0.1");
  const OptionValues s = study::resolved_options("shadows", {{"sampling", std::string("conventional,peeling")}});
  EXPECT_EQ(s.at("sampling"), OptionValue(std::string("conventional,peeling")));
}

}  // namespace
}  // namespace proxima
