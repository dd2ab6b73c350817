// The env-map reflection study called directly on small renders: rectified lookups err
// less than plain ones and find the reference's object more often, every method's figures
// stay in range, --layers bounds the maps built, bad options are refused naming the flag
// before anything is written, and 1 and 2 threads give the same metrics and image bits.
#include "proxima/study/envmap_reflect.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/limits.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/builtin_scenes.h"
#include "study_test_util.h"
#include "test_util.h"

namespace proxima {
namespace {

// A small run: 96×72 pixels, 64² cube faces, one area-light sample, one timed frame.
study::EnvmapReflectOptions small_options() {
  study::EnvmapReflectOptions o;
  o.compare = true;
  o.width = 96;
  o.height = 72;
  o.cube_size = 64;
  o.light_samples = 1;
  o.reps = 1;
  return o;
}

double metric(const Results& r, const std::string& name) {
  const auto it = r.metrics.find(name);
  EXPECT_NE(it, r.metrics.end()) << name;
  return it == r.metrics.end() ? std::nan("") : it->second;
}

bool is_timing(const std::string& name) { return name.find("_ms") != std::string::npos; }

TEST(EnvmapReflectStudy, RectifiedErrsLessThanPlainOnRoomReflector) {
  const Scene scene = make_builtin_scene("room-reflector");
  const Results r = study::run_envmap_reflect(scene, small_options(), {});
  EXPECT_GT(metric(r, "reflector_pixels"), 500.0);
  EXPECT_GT(metric(r, "envmap_mae"), 5.0);  // plain env mapping misses the parallax near the walls
  EXPECT_LT(metric(r, "rectified_mae"), metric(r, "envmap_mae") / 3.0);
  EXPECT_LT(metric(r, "layered_mae"), metric(r, "envmap_mae") / 3.0);
  EXPECT_LT(metric(r, "average_mae"), metric(r, "envmap_mae"));
  EXPECT_GT(metric(r, "rectified_object_match_pct"), metric(r, "envmap_object_match_pct"));
  EXPECT_EQ(metric(r, "reference_mae"), 0.0);
  EXPECT_EQ(metric(r, "N"), 12.0);  // ⌈log2(2 · 12 m / 0.01 m)⌉, the room's diagonal as D
  ASSERT_EQ(r.tables.size(), 1u);
  EXPECT_EQ(r.tables[0].rows.size(), std::size(study::kEnvmapReflectMethods));
  EXPECT_TRUE(r.images.empty());  // no output directory: nothing written
}

TEST(EnvmapReflectStudy, FiguresStayInTheirRanges) {
  const Scene scene = make_builtin_scene("room-parallax");
  study::EnvmapReflectOptions o = small_options();
  o.camera.camera = "left";
  const Results r = study::run_envmap_reflect(scene, o, {});
  for (const char* m : study::kEnvmapReflectMethods) {
    const std::string name(m);
    const double match = metric(r, name + "_object_match_pct");
    EXPECT_GE(match, 0.0) << m;
    EXPECT_LE(match, 100.0) << m;
    EXPECT_GE(metric(r, name + "_mae"), 0.0) << m;
    EXPECT_GE(metric(r, name + "_env_mae"), 0.0) << m;
    if (name == "reference") continue;
    EXPECT_LT(match, 100.0) << m << ": the map's texels cannot all match at 64²";
    EXPECT_GE(metric(r, name + "_edge_pct"), 0.0) << m;
    EXPECT_LE(metric(r, name + "_edge_pct"), 100.0) << m;
    EXPECT_GE(metric(r, name + "_samples_per_lookup"), 1.0) << m;
  }
  EXPECT_EQ(metric(r, "reference_object_match_pct"), 100.0);
  EXPECT_GE(metric(r, "self_reflection_pct"), 0.0);
  EXPECT_LE(metric(r, "self_reflection_pct"), 100.0);
  EXPECT_GE(metric(r, "layered_fallback_pct"), 0.0);
  EXPECT_LE(metric(r, "layered_fallback_pct"), 100.0);
  // Layered maps show the sphere's far side that the single map's center cannot see.
  EXPECT_GT(metric(r, "layered_object_match_pct"), metric(r, "envmap_object_match_pct"));
}

TEST(EnvmapReflectStudy, LayersBoundTheMapsBuilt) {
  const Scene scene = make_builtin_scene("room-parallax");
  for (int k : {1, 2}) {
    study::EnvmapReflectOptions o = small_options();
    o.compare = false;
    o.method = "layered";
    o.layers = k;
    const Results r = study::run_envmap_reflect(scene, o, {});
    EXPECT_EQ(metric(r, "layers"), double(k));  // the sphere hides the room behind it
    EXPECT_GT(metric(r, "layer0_shaded_texels"), 0.0);
    EXPECT_EQ(r.metrics.count("layer1_shaded_texels"), k == 2 ? 1u : 0u);
    EXPECT_EQ(r.metrics.count("envmap_mae"), 0u);  // one method: only its figures
    EXPECT_EQ(r.metrics.count("envmap_build_ms"), 0u);
  }
}

TEST(EnvmapReflectStudy, BadOptionsAreRefusedNamingTheFlag) {
  const Scene scene = make_builtin_scene("room-reflector");
  auto with = [](auto change) {
    study::EnvmapReflectOptions o = small_options();
    change(o);
    return o;
  };
  const std::pair<study::EnvmapReflectOptions, const char*> cases[] = {
      {with([](auto& o) { o.method = "mirror"; }), "--method"},
      {with([](auto& o) { o.method = "cluster"; }), "--method"},  // the command's, not this study's
      {with([](auto& o) { o.d_e = 0.0f; }), "--d-e"},
      {with([](auto& o) { o.edge = "grey"; }), "--edge"},
      {with([](auto& o) { o.cube_size = 0; }), "--cube-size"},
      {with([](auto& o) { o.cube_size = kMaxImageSide + 1; }), "--cube-size"},
      {with([](auto& o) { o.layers = 17; }), "--layers"},
      {with([](auto& o) { o.march_steps = 0; }), "--march-steps"},
      {with([](auto& o) { o.reps = 0; }), "--reps"},
      {with([](auto& o) { o.max_maps = 0; }), "--max-maps"},
      {with([](auto& o) { o.max_maps = kMaxEnvmapGroups + 1; }), "--max-maps"},
      {with([](auto& o) { o.group_parallax = -1.0f; }), "--group-parallax"},
      {with([](auto& o) { o.camera.camera = "nowhere"; }), "--camera"},
      {with([](auto& o) { o.width = kMaxImageSide + 1; }), "--width"},
  };
  for (const auto& [o, flag] : cases) {
    TempDir dir;
    const std::string message =
        error_of([&] { study::run_envmap_reflect(scene, o, study::StudyOutput{dir.path / "never"}); });
    EXPECT_EQ(message.rfind(flag, 0), 0u) << flag << ": " << message;
    EXPECT_FALSE(std::filesystem::exists(dir.path / "never")) << flag;
  }
  EXPECT_EQ(error_of([&] { study::validate(small_options()); }), "");
  EXPECT_EQ(error_of([&] { study::validate(small_options(), scene); }), "");
  const std::string no_reflector =
      error_of([&] { study::validate(small_options(), make_builtin_scene("nest")); });
  EXPECT_EQ(no_reflector.rfind("--scene: 'nest' has no reflective object", 0), 0u) << no_reflector;
}

TEST(EnvmapReflectStudy, MapsBeyondTheMemoryLimitAreRefused) {
  const Limits saved = limits();
  set_limits({saved.max_triangles, 1024});
  study::EnvmapReflectOptions o = small_options();
  o.cube_size = 2048;  // 6 faces × 24 bytes per texel × (1 map + 3 layers): 2304 MiB
  const std::string message = error_of([&] { study::validate(o); });
  o.compare = false;  // rectified alone: one map, 576 MiB
  const std::string one_map = error_of([&] { study::validate(o); });
  set_limits(saved);
  EXPECT_EQ(message.rfind("--cube-size: ", 0), 0u) << message;
  EXPECT_NE(message.find("--max-memory-mb"), std::string::npos) << message;
  EXPECT_EQ(one_map, "");
}

// A map per group of reflectors; the group metrics appear only with more than one
// reflector (a single one keeps the shared map's metrics and bits).
TEST(EnvmapReflectStudy, MultiReflectorScenesReportTheirMaps) {
  const Scene scene = make_builtin_scene("cornell");
  ASSERT_EQ(reflective_objects(scene).size(), 2u);
  study::EnvmapReflectOptions o = small_options();
  o.method = "rectified";
  o.compare = false;
  const Results own = study::run_envmap_reflect(scene, o, {});
  o.max_maps = 1;
  const Results shared = study::run_envmap_reflect(scene, o, {});
  EXPECT_EQ(metric(shared, "maps"), 1.0);
  EXPECT_EQ(metric(shared, "map0_reflectors"), 2.0);
  const double maps = metric(own, "maps");
  EXPECT_GE(maps, 1.0);
  EXPECT_LE(maps, 2.0);
  double reflectors = 0.0;
  for (int g = 0; g < int(maps); ++g) {
    reflectors += metric(own, "map" + std::to_string(g) + "_reflectors");
    EXPECT_GE(metric(own, "map" + std::to_string(g) + "_parallax"), 0.0);
  }
  EXPECT_EQ(reflectors, 2.0);
  const Results single = study::run_envmap_reflect(make_builtin_scene("room-reflector"), small_options(), {});
  EXPECT_EQ(single.metrics.count("maps"), 0u);
}

TEST(EnvmapReflectStudy, OneAndTwoThreadsGiveTheSameMetricsAndImageBits) {
  const Scene scene = make_builtin_scene("room-parallax");
  study::EnvmapReflectOptions o = small_options();
  o.camera.camera = "left";
  o.glossy_rays = 2;
  TempDir a, b;
  Results r1, r2;
  {
    ThreadLimit limit(1);
    r1 = study::run_envmap_reflect(scene, o, study::StudyOutput{a.path});
  }
  {
    ThreadLimit limit(2);
    r2 = study::run_envmap_reflect(scene, o, study::StudyOutput{b.path});
  }
  ASSERT_EQ(r1.metrics.size(), r2.metrics.size());
  for (const auto& [name, value] : r1.metrics) {
    if (is_timing(name)) continue;
    EXPECT_EQ(value, r2.metrics.at(name)) << name;
  }
  ASSERT_EQ(r1.images, r2.images);
  EXPECT_EQ(r1.images.size(), 2 * std::size(study::kEnvmapReflectMethods) - 1);  // error_<m> for all but the reference
  for (const auto& [role, file] : r1.images) {
    const std::string bytes = file_bytes(a.path / file);
    EXPECT_GT(bytes.size(), 100u) << file;
    EXPECT_EQ(bytes, file_bytes(b.path / file)) << file;
  }
}

TEST(EnvmapReflectStudy, ReportsProgressPerStage) {
  const Scene scene = make_builtin_scene("room-reflector");
  study::EnvmapReflectOptions o = small_options();
  o.compare = false;
  o.reps = 2;
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  {
    Progress progress(log, false);
    study::run_envmap_reflect(scene, o, {}, &progress);
  }
  std::rewind(log);
  std::string text;
  for (int ch; (ch = std::fgetc(log)) != EOF;) text += char(ch);
  std::fclose(log);
  for (const char* step : {"reference", "maps", "frames", "timing 1/2", "timing 2/2"})
    EXPECT_NE(text.find(step), std::string::npos) << step << " in\n" << text;
}

}  // namespace
}  // namespace proxima
