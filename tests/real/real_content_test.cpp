// The real-content tier (`make test-real`, docs/real-content.md): every technique on the
// scenes scripts/real-content.sh builds from models no one here wrote, held to the bounds
// the built-in scenes are held to (docs/RESULTS.md and docs/journal/). Skipped when
// PROXIMA_REAL_CONTENT (the corpus directory) is unset, failed when it names no corpus. Each run keeps its output (images,
// results.json) in $PROXIMA_REAL_CONTENT/out/<run>.
// Every bound fails the test when missed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iostream>
#include <sstream>
#include <string>
#include <variant>

#include "cli/cli_util.h"
#include "proxima/eval/results.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

// The corpus directory named by PROXIMA_REAL_CONTENT, or empty when it is unset (the tier
// does not run here).
fs::path corpus() {
  const char* dir = std::getenv("PROXIMA_REAL_CONTENT");
  return dir ? fs::path(dir) : fs::path();
}

// Skips the test when PROXIMA_REAL_CONTENT is unset; fails it when the variable names no
// corpus (a tier asked for must not pass by skipping).
#define REQUIRE_CORPUS()                                                                            \
  const fs::path dir = corpus();                                                                    \
  if (dir.empty()) GTEST_SKIP() << "PROXIMA_REAL_CONTENT is unset (make test-real sets it)";        \
  ASSERT_TRUE(fs::exists(dir / "house.json")) << "PROXIMA_REAL_CONTENT=" << dir                     \
                                              << " is not a corpus: run scripts/real-content.sh --out " << dir

// `proxima COMMAND --scene SCENE ARGS --out DIR/out/RUN` with SCENE a file of the corpus
// (run) or a built-in scene's name (run_builtin); the run must succeed. Returns its
// results.json.
Results run_scene(const fs::path& dir, const std::string& run_name, const std::string& command,
                  const std::string& scene, const std::string& args) {
  const fs::path out = dir / "out" / run_name;
  fs::remove_all(out);
  const std::string cmd = command + " --scene " + scene + " " + args + " --out " + out.string();
  std::cout << "[real-content] proxima " << cmd << "\n";
  const RunResult r = run_cli(cmd);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  if (r.exit_code != 0) return {};
  return read_results_json(out / "results.json");
}
Results run(const fs::path& dir, const std::string& run_name, const std::string& command, const std::string& scene,
            const std::string& args) {
  return run_scene(dir, run_name, command, (dir / scene).string(), args);
}

double metric(const Results& r, const std::string& name) {
  auto it = r.metrics.find(name);
  EXPECT_NE(it, r.metrics.end()) << "no metric " << name;
  return it == r.metrics.end() ? std::nan("") : it->second;
}

std::string figure(const std::string& what, double measured, const char* op, double bound) {
  std::ostringstream s;
  s << what << ": " << measured << " (bound " << op << " " << bound << ")";
  return s.str();
}

// A bound that holds on the built-in scenes: fails the test when missed.
void expect_le(const std::string& what, double measured, double bound) {
  std::cout << "[real-content] " << figure(what, measured, "≤", bound) << "\n";
  EXPECT_LE(measured, bound) << what;
}
void expect_ge(const std::string& what, double measured, double bound) {
  std::cout << "[real-content] " << figure(what, measured, "≥", bound) << "\n";
  EXPECT_GE(measured, bound) << what;
}

// Every scene renders, the same bits at 1 and 2 threads (DESIGN.md determinism), and the
// camera sees geometry (trees: sky above the horizon).
TEST(RealContent, ReferenceRendersEveryScene) {
  REQUIRE_CORPUS();
  for (const char* scene : {"house", "trees", "gallery"}) {
    const std::string args = "--camera main --width 160 --height 120 --spp 1";
    const Results a = run(dir, std::string("render-") + scene + "-t1", "render --threads 1", std::string(scene) + ".json", args);
    const Results b = run(dir, std::string("render-") + scene + "-t2", "render --threads 2", std::string(scene) + ".json", args);
    expect_ge(std::string(scene) + " coverage_pct", metric(a, "coverage_pct"), 10.0);  // the camera sees the model
    for (const char* file : {"color.exr", "depth.exr", "id.exr"}) {
      std::ifstream fa(dir / "out" / (std::string("render-") + scene + "-t1") / file, std::ios::binary);
      std::ifstream fb(dir / "out" / (std::string("render-") + scene + "-t2") / file, std::ios::binary);
      const std::string da((std::istreambuf_iterator<char>(fa)), {}), db((std::istreambuf_iterator<char>(fb)), {});
      EXPECT_FALSE(da.empty()) << scene << " " << file;
      EXPECT_TRUE(da == db) << scene << " " << file << " differs between 1 and 2 threads";
    }
  }
}

// Environment maps with distance: rectified ≤ 1/3 of plain's error; layered at or below
// rectified's, with the default 512² cube faces at 640 × 480 and with 128² faces at
// 320 × 240 (where neighbouring texels of a seam seen at a grazing angle differ most).
// The layered/single build-time ratio is printed, not asserted (timings belong to runs
// measured side by side, not to tests); docs/real-content.md has the measured ratio.
TEST(RealContent, EnvMapsOnTheHouseWithAMirrorSphere) {
  REQUIRE_CORPUS();
  const Results r = run(dir, "envmap-house-sphere", "reflect", "house-sphere.json",
                        "--camera sphere --compare --width 640 --height 480 --light-samples 2 --reps 1");
  const double plain = metric(r, "envmap_mae"), rect = metric(r, "rectified_mae"), layered = metric(r, "layered_mae");
  expect_ge("house-sphere reflector_pixels", metric(r, "reflector_pixels"), 1000.0);
  expect_le("house-sphere rectified_mae vs envmap_mae / 3", rect, plain / 3.0);
  expect_le("house-sphere layered_mae vs rectified_mae", layered, rect);
  std::cout << "[real-content] house-sphere layered_build_ms / envmap_build_ms: "
            << metric(r, "layered_build_ms") / metric(r, "envmap_build_ms") << " (target ≤ 2, not asserted)\n";
  const Results small = run(dir, "envmap-house-sphere-128", "reflect", "house-sphere.json",
                            "--camera sphere --compare --width 320 --height 240 --cube-size 128 --light-samples 2 --reps 1");
  const double rect128 = metric(small, "rectified_mae"), layered128 = metric(small, "layered_mae");
  expect_le("house-sphere 128² faces layered_mae vs rectified_mae", layered128, rect128);
}

// The gallery's three reflectors far apart (mirror sphere, wall mirror, glossy floor) get a
// map each (envmap_groups.h), so the bound of single compact reflectors applies.
TEST(RealContent, EnvMapsInTheGallery) {
  REQUIRE_CORPUS();
  const Results r = run(dir, "envmap-gallery", "reflect", "gallery.json",
                        "--camera mirror --compare --width 320 --height 240 --cube-size 128 --light-samples 2 --reps 1");
  expect_ge("gallery reflector_pixels", metric(r, "reflector_pixels"), 1000.0);
  expect_ge("gallery maps", metric(r, "maps"), 3.0);
  const double plain = metric(r, "envmap_mae"), rect = metric(r, "rectified_mae");
  expect_le("gallery rectified_mae vs envmap_mae / 3", rect, plain / 3.0);
}

// Cluster depth-image reflections: mean error per channel ≤ 6 / 3 / 9 (the
// thesis'), occlusion-error samples ≤ 3 % on average.
void expect_cluster_bounds(const fs::path& dir, const std::string& scene) {
  const Results r = run(dir, "cluster-" + scene, "reflect --method cluster", scene + ".json",
                        "--path walk --frames 100 --frame-step 50 --width 256 --height 192 --ss 2 --compare");
  const char* ch[] = {"r", "g", "b"};
  const double bound[] = {6.0, 3.0, 9.0};
  for (int c = 0; c < 3; ++c)
    expect_le(scene + " cluster_mae_" + ch[c], metric(r, std::string("cluster_mae_") + ch[c]), bound[c]);
  expect_le(scene + " occlusion_error_pct_avg", metric(r, "occlusion_error_pct_avg"), 3.0);
}
TEST(RealContent, ClusterReflectionsInTheHouse) {
  REQUIRE_CORPUS();
  expect_cluster_bounds(dir, "house");
}
TEST(RealContent, ClusterReflectionsInTheGallery) {
  REQUIRE_CORPUS();
  expect_cluster_bounds(dir, "gallery");
}

// Temporal reuse of reflections: mean error ≤ 1.0 on 0–255, ≤ 25 % of the reflective
// pixels recomputed, below direct reprojection's error. Path `pan`: 1.6 m in 100 frames, the
// camera speed per frame of the built-in runs (living-room / walk, 500 frames).
Results temporal_run(const fs::path& dir, const std::string& scene, int side) {
  const std::string px = std::to_string(side);
  return run(dir, "temporal-" + scene + "-" + px, "reflect --method temporal", scene + ".json",
             "--path pan --frames 100 --width " + px + " --height " + px + " --compare");
}
void expect_temporal_bounds(const fs::path& dir, const std::string& scene, int side) {
  const Results r = temporal_run(dir, scene, side);
  const std::string what = scene + " " + std::to_string(side) + "² temporal_";
  const double mae = metric(r, "temporal_mae_avg");
  expect_le(what + "mae_avg vs direct_mae_avg", mae, metric(r, "direct_mae_avg"));
  expect_le(what + "mae_avg", mae, 1.0);
  expect_le(what + "recompute_pct_avg", metric(r, "recompute_pct_avg"), 25.0);
}
// The bounds are the built-in scenes' at 1024² (living-room / walk: 0.68, 14.8 %). Pixels a
// few times larger than the mirrored detail cost reuse on every scene: the built-in
// living-room walk misses both bounds up to 192² (docs/real-content.md). So the house is held
// to them at 192², and at 96² to the built-in living-room walk at the same size and speed.
TEST(RealContent, TemporalReuseInTheHouse) {
  REQUIRE_CORPUS();
  expect_temporal_bounds(dir, "house", 192);
  const Results house = temporal_run(dir, "house", 96);
  const Results living_room = run_scene(dir, "temporal-living-room-96", "reflect --method temporal", "living-room",
                                        "--path walk --frames 500 --width 96 --height 96 --compare");
  for (const char* m : {"temporal_mae_avg", "recompute_pct_avg"})
    expect_le(std::string("house 96² ") + m + " vs living-room walk's", metric(house, m), metric(living_room, m));
  expect_le("house 96² temporal_mae_avg vs direct_mae_avg", metric(house, "temporal_mae_avg"),
            metric(house, "direct_mae_avg"));
}
TEST(RealContent, TemporalReuseInTheGallery) {
  REQUIRE_CORPUS();
  expect_temporal_bounds(dir, "gallery", 96);
}

// Soft shadows from reconstructed depth images: NRR's mean visibility error below
// conventional's (the bound is set at ref-res 1024; on the trees it holds from 512 on and
// misses by 0.02 at 256: docs/real-content.md).
void expect_shadow_bounds(const fs::path& dir, const std::string& scene) {
  const Results r = run(dir, "shadows-" + scene, "shadows", scene + ".json",
                        "--sampling nrr,conventional,peeling --ref-res 512 --out-res 256 --light-samples 4 --no-images");
  const double nrr = metric(r, "nrr_visibility_error_mean"), conv = metric(r, "conventional_visibility_error_mean");
  std::cout << "[real-content] " << scene << " peeling_visibility_error_mean: " << metric(r, "peeling_visibility_error_mean") << "\n";
  expect_le(scene + " nrr_visibility_error_mean vs conventional's", nrr, conv);
}
TEST(RealContent, SoftShadows) {
  REQUIRE_CORPUS();
  for (const char* scene : {"house", "trees", "gallery"}) expect_shadow_bounds(dir, scene);
}

// Depth-image sampling: NRR images hold no sample redundant with an earlier image
// under their own definition, nor do depth-peeling layers under pixel redundancy. The
// available samples per output frame are printed (the thesis' claim, docs/real-content.md).
void expect_sampling_bounds(const fs::path& dir, const std::string& scene) {
  const Results r = run(dir, "sample-" + scene, "sample", scene + ".json",
                        "--method conventional,peeling,nrr-pixel --width 128 --frames 50 --no-images");
  for (int i = 1; i < 3; ++i) {
    const std::string k = std::to_string(i);
    expect_le(scene + " nrr_pixel_redundant_pct_" + k, metric(r, "nrr_pixel_redundant_pct_" + k), 0.0);
    expect_le(scene + " peeling_redundant_pct_" + k, metric(r, "peeling_redundant_pct_" + k), 0.0);
  }
  for (const char* m : {"conventional", "peeling", "nrr_pixel"})
    std::cout << "[real-content] " << scene << " " << m << "_available_avg_pct: " << metric(r, std::string(m) + "_available_avg_pct") << "\n";
  const Results v = run(dir, "sample-visibility-" + scene, "sample", scene + ".json",
                        "--method nrr-visibility --width 128 --frames 20 --no-images");
  for (int i = 1; i < 3; ++i)
    expect_le(scene + " nrr-visibility redundant_pct_" + std::to_string(i), metric(v, "redundant_pct_" + std::to_string(i)), 0.0);
}
TEST(RealContent, SamplingTreesAndPlants) {
  REQUIRE_CORPUS();
  for (const char* scene : {"trees", "tree-maple", "plant-yucca"}) expect_sampling_bounds(dir, scene);
}
TEST(RealContent, SamplingTheGallery) {
  REQUIRE_CORPUS();
  expect_sampling_bounds(dir, "gallery");
}

// Exact visibility maps on the corpus' building: at every viewpoint agreement with Embree
// ≥ 99.9 %, ≥ 99.99 % away from map edges (coplanar and snap ties counting as agreement, as
// on the brush levels: docs/visibility.md, "What the map is exact for"); no sample labelled
// with an occluded polygon; every map passing its self-check; no fragment the BSP could not
// place.
TEST(RealContent, ExactVisibilityInTheHouse) {
  REQUIRE_CORPUS();
  const Results r = run(dir, "visibility-house", "visibility", "house-bare.json",
                        "--path walk --frames 10 --width 256 --height 192 --no-images");
  ASSERT_EQ(metric(r, "viewpoints"), 10.0);
  expect_ge("house worst view agreement_with_ties_pct", metric(r, "agreement_with_ties_pct_worst"), 99.9);
  expect_ge("house worst view agreement_interior_with_ties_pct", metric(r, "agreement_interior_with_ties_pct_worst"),
            99.99);
  expect_le("house occluded_label_samples", metric(r, "occluded_label_samples"), 0.0);
  std::cout << "[real-content] house beams_avg " << metric(r, "beams_avg") << ", worst view agreement_pct (no ties) "
            << metric(r, "agreement_pct_worst") << "\n";
  expect_le("house unplaced_fragments", metric(r, "unplaced_fragments"), 0.0);
  expect_le("house maps_failed_selfcheck", metric(r, "maps_failed_selfcheck"), 0.0);
}

// Hybrid geometry- and image-based rendering: visibility-map mapping beats
// item-buffer mapping in PSNR and near silhouettes.
TEST(RealContent, GibrInTheHouse) {
  REQUIRE_CORPUS();
  const Results r = run(dir, "gibr-house", "gibr", "house-bare.json",
                        "--photos 8 --views path --frames 2 --width 160 --height 120 --photo-width 160 --photo-height 120");
  const double pv = metric(r, "psnr_vismap"), pi = metric(r, "psnr_itembuffer");
  const double sv = metric(r, "silhouette_mae_vismap"), si = metric(r, "silhouette_mae_itembuffer");
  expect_ge("house psnr_vismap vs psnr_itembuffer", pv, pi);
  expect_le("house silhouette_mae_vismap vs silhouette_mae_itembuffer", sv, si);
}

}  // namespace
}  // namespace proxima
