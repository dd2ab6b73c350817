// Self-check of visibility maps: passes on the built-in models' maps, fires on maps
// corrupted on purpose (a region removed, relabeled, set to background; a malformed
// region), and `proxima visibility --strict` exits 3 on a winged pair with a wall made
// transparent.
#include "proxima/visibility/map_check.h"

#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_util.h"
#include "proxima/gibr/gibr_model.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/winged_pair_io.h"

namespace proxima::visibility {
namespace {

struct Traced {
  Scene scene;
  ModelPolygons model;
  WingedPair wp;
  std::unique_ptr<RayScene> rays;
};

Traced trace_model(const std::string& name) {
  Traced t;
  t.scene = make_builtin_scene(name);
  t.model = extract_polygons(t.scene);
  t.wp = build_winged_pair(t.model);
  t.rays = std::make_unique<RayScene>(t.scene);
  return t;
}

Camera frame_camera(const Scene& s, int frame, int frames, int w, int h) {
  const CameraPath& p = s.camera_paths.front();
  return camera_at_time(p, frame_time(p, frame * (p.frames - 1) / std::max(1, frames - 1)), w, h, 1e-3f, 1e4f);
}

// Index of the largest region showing a polygon (the corruptions below act on it).
size_t largest_polygon_region(const VisibilityMap& map) {
  size_t best = 0;
  double best_area = -1;
  for (size_t r = 0; r < map.regions.size(); ++r)
    if (map.regions[r].polygon != kNone && region_area(map.regions[r]) > best_area) {
      best_area = region_area(map.regions[r]);
      best = r;
    }
  return best;
}

// Every built-in model's maps pass at 5 viewpoints spread over the walk, 256 × 192; the
// check's time is printed beside the map's.
TEST(MapCheck, PassesOnTheBuiltInModels) {
  for (const char* name : {"rooms", "maze", "arena", "vcity", "floor"}) {
    const Traced t = trace_model(name);
    double map_ms = 0, check_ms = 0;
    size_t judged = 0;
    for (int k = 0; k < 5; ++k) {
      const Camera cam = frame_camera(t.scene, k, 5, 256, 192);
      const VisibilityMap map = trace_visibility_map(t.wp, cam);
      const MapCheck c = check_visibility_map(map, t.model, *t.rays, cam);
      EXPECT_TRUE(c.pass) << name << " view " << k << ": " << c.reason;
      // Welding moves input vertices by up to the snap tolerance, which can leave slivers of
      // ~1e-5 px² uncovered (maze: 1.1e-9 of the image); a crack a pixel center can fall in
      // is ≥ 1e-3 of a pixel row, far above this bound.
      EXPECT_NEAR(c.area_ratio, 1.0, 1e-8) << name;
      EXPECT_GE(c.samples, 64u) << name << ": most samples are judged";
      judged += c.samples;
      map_ms += map.stats.ms;
      check_ms += c.ms;
    }
    std::printf("%s: map %.2f ms, self-check %.3f ms per view, %zu samples judged\n", name, map_ms / 5, check_ms / 5,
                judged);
  }
}

class CorruptedMap : public ::testing::Test {
 protected:
  void SetUp() override {
    t_ = trace_model("rooms");
    cam_ = frame_camera(t_.scene, 0, 1, 256, 192);
    map_ = trace_visibility_map(t_.wp, cam_);
    ASSERT_TRUE(check_visibility_map(map_, t_.model, *t_.rays, cam_).pass);
    big_ = largest_polygon_region(map_);
    ASSERT_GT(region_area(map_.regions[big_]), 0.05 * 256 * 192) << "a region large enough for the sparse rays";
  }
  Traced t_;
  Camera cam_;
  VisibilityMap map_;
  size_t big_ = 0;
};

TEST_F(CorruptedMap, RegionRemovedFailsTheAreaCheck) {
  map_.regions.erase(map_.regions.begin() + std::ptrdiff_t(big_));
  const MapCheck c = check_visibility_map(map_, t_.model, *t_.rays, cam_);
  EXPECT_FALSE(c.pass);
  EXPECT_LT(c.area_ratio, 0.95);
  EXPECT_NE(c.reason.find("area"), std::string::npos) << c.reason;
  EXPECT_GT(c.uncovered, 0u);
}

TEST_F(CorruptedMap, RegionRelabeledFailsTheRays) {
  const uint32_t p = map_.regions[big_].polygon;
  map_.regions[big_].polygon = (p + 1) % uint32_t(t_.model.polygons.size());
  const MapCheck c = check_visibility_map(map_, t_.model, *t_.rays, cam_);
  EXPECT_FALSE(c.pass);
  EXPECT_GT(c.mismatches, 0u);
  EXPECT_EQ(c.background_on_geometry, 0u);
  EXPECT_NE(c.reason.find("disagree with Embree"), std::string::npos) << c.reason;
}

TEST_F(CorruptedMap, RegionSetToBackgroundFailsTheRays) {
  map_.regions[big_].polygon = kNone;
  const MapCheck c = check_visibility_map(map_, t_.model, *t_.rays, cam_);
  EXPECT_FALSE(c.pass);
  EXPECT_GT(c.background_on_geometry, 0u);
  EXPECT_NE(c.reason.find("background where Embree hits geometry"), std::string::npos) << c.reason;
}

TEST_F(CorruptedMap, DuplicatedRegionFailsAsOverlap) {
  map_.regions.push_back(map_.regions[big_]);
  const MapCheck c = check_visibility_map(map_, t_.model, *t_.rays, cam_);
  EXPECT_FALSE(c.pass);
  EXPECT_GT(c.area_ratio, 1.05);
  EXPECT_NE(c.reason.find("overlaps"), std::string::npos) << c.reason;
  EXPECT_GT(c.multiply_covered, 0u);
}

TEST_F(CorruptedMap, MalformedRegionsFailTheSanityCheck) {
  VisibilityMap bad = map_;
  bad.regions[0].polygon = uint32_t(t_.model.polygons.size()) + 7;
  EXPECT_NE(check_visibility_map(bad, t_.model, *t_.rays, cam_).reason.find("labeled polygon"), std::string::npos);
  bad = map_;
  bad.regions[0].vertices.resize(2);
  EXPECT_FALSE(check_visibility_map(bad, t_.model, *t_.rays, cam_).pass);
  bad = map_;
  bad.regions[0].vertices[0].x = std::nan("");
  EXPECT_NE(check_visibility_map(bad, t_.model, *t_.rays, cam_).reason.find("outside the image"), std::string::npos);
  bad = map_;
  std::reverse(bad.regions[big_].vertices.begin(), bad.regions[big_].vertices.end());
  EXPECT_NE(check_visibility_map(bad, t_.model, *t_.rays, cam_).reason.find("negative area"), std::string::npos);
  bad = map_;
  bad.width = 0;
  EXPECT_FALSE(check_visibility_map(bad, t_.model, *t_.rays, cam_).pass);
}

TEST(MapCheck, Deterministic) {
  const Traced t = trace_model("maze");
  const Camera cam = frame_camera(t.scene, 3, 5, 200, 150);
  const VisibilityMap map = trace_visibility_map(t.wp, cam);
  const MapCheck a = check_visibility_map(map, t.model, *t.rays, cam), b = check_visibility_map(map, t.model, *t.rays, cam);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.skipped_near_edge, b.skipped_near_edge);
  EXPECT_EQ(a.mismatches, b.mismatches);
}

// The CLI: a winged pair of `rooms` whose faces on the polygon filling most of frame 0
// are made transparent (polygon −1 in the file) traces a map that shows what lies behind
// that polygon; the self-check fails it, the warning names the frame, results.json counts
// it, and --strict turns that into exit code 3 (without --strict: 0).
TEST(MapCheckCli, StrictExitsNonZeroOnAFailingMap) {
  TempDir dir;
  const auto good = dir.path / "rooms.wp", bad = dir.path / "rooms_bad.wp";
  RunResult save = run_cli("visibility --scene rooms --frames 1 --width 128 --height 96 --no-images --save " +
                           good.string() + " --out " + (dir.path / "save").string());
  ASSERT_EQ(save.exit_code, 0) << save.output;
  EXPECT_NE(save.output.find("maps_failed_selfcheck"), std::string::npos) << save.output;

  const Traced t = trace_model("rooms");
  const Camera cam = frame_camera(t.scene, 0, 1, 128, 96);
  const VisibilityMap map = trace_visibility_map(t.wp, cam);
  const uint32_t victim = map.regions[largest_polygon_region(map)].polygon;

  // Rewrite the faces block: field 4 of a face line is its polygon.
  std::ifstream in(good);
  std::ostringstream out;
  std::string line;
  size_t faces_left = 0, flipped = 0;
  while (std::getline(in, line)) {
    if (faces_left > 0) {
      --faces_left;
      std::istringstream fields(line);
      std::string c0, c1, pair, polygon;
      fields >> c0 >> c1 >> pair >> polygon;
      if (polygon == std::to_string(victim)) {
        std::string rest;
        std::getline(fields, rest);
        line = c0 + " " + c1 + " " + pair + " -1" + rest;
        ++flipped;
      }
    } else if (line.rfind("faces ", 0) == 0) {
      faces_left = std::stoul(line.substr(6));
    }
    out << line << "\n";
  }
  ASSERT_GT(flipped, 0u);
  write_file(bad, out.str());

  const std::string args = "visibility --scene rooms --frames 1 --width 128 --height 96 --no-images --load " + bad.string();
  RunResult lax = run_cli(args + " --out " + (dir.path / "lax").string());
  EXPECT_EQ(lax.exit_code, 0) << lax.output;
  EXPECT_NE(lax.output.find("frame 0"), std::string::npos) << lax.output;
  EXPECT_NE(lax.output.find("failed its self-check"), std::string::npos) << lax.output;
  std::ifstream results(dir.path / "lax" / "results.json");
  const nlohmann::json j = nlohmann::json::parse(results);
  EXPECT_EQ(j["metrics"]["maps_failed_selfcheck"].get<double>(), 1.0);

  RunResult strict = run_cli(args + " --strict --out " + (dir.path / "strict").string());
  EXPECT_EQ(strict.exit_code, 3) << strict.output;
}

TEST(MapCheckCli, BadSelfcheckRaysIsAnInputError) {
  TempDir dir;
  RunResult r = run_cli("visibility --scene rooms --frames 1 --width 32 --height 24 --selfcheck-rays 0 --out " +
                        dir.path.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--selfcheck-rays"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.path / "results.json"));
}

// GIBR checks the visibility map of every photograph the same way.
TEST(MapCheck, GibrChecksEveryPhotographsMap) {
  gibr::GibrModelOptions o;
  o.photos = 3;
  o.photo_width = 64;
  o.photo_height = 48;
  o.supersample = 1;
  const gibr::GibrModel g = gibr::build_gibr_model(make_builtin_scene("rooms"), o);
  EXPECT_EQ(g.stats.maps_failed_selfcheck, 0u);
  EXPECT_TRUE(g.stats.selfcheck_failures.empty());
  EXPECT_GT(g.stats.selfcheck_ms, 0.0);
}

}  // namespace
}  // namespace proxima::visibility
