// study/cluster_reflect.h on tiny runs: errors against Embree on the same rays, the
// occlusion-error causes, determinism across thread counts, and options checked by name.
#include "proxima/study/cluster_reflect.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/scene/load.h"
#include "test_util.h"
#include "study_test_util.h"

namespace proxima {

namespace {

double cell(const Results& r, const std::string& title_start, size_t row, const std::string& column) {
  for (const Table& t : r.tables) {
    if (t.title.rfind(title_start, 0) != 0) continue;
    for (size_t c = 0; c < t.columns.size(); ++c)
      if (t.columns[c] == column) return std::get<double>(t.rows.at(row).at(c));
  }
  ADD_FAILURE() << "no column " << column << " in a table '" << title_start << "...'";
  return 0.0;
}

}  // namespace

TEST(ClusterReflectStudy, ErrorsAgainstEmbreeOnTheSameRaysAreSmall) {
  const Scene scene = load_scene("room-reflector");
  const Results r = study::run_cluster_reflect(scene, tiny_cluster_options(), {});
  const auto& m = r.metrics;
  EXPECT_EQ(m.at("frames"), 2.0);
  EXPECT_EQ(m.at("frames_with_reflections"), 2.0);
  EXPECT_GE(m.at("clusters_avg"), 1.0);
  // Worst channel of the worst frame, 0–255 over the reflective pixels (7.6 measured at this
  // coarse size: cluster images of a 48×32 frame hold few texels).
  const double cluster_max = cell(r, "Error vs Embree", 0, "mae_max_channel_max_frame");
  EXPECT_GT(cluster_max, 0.0);
  EXPECT_LT(cluster_max, 10.0);
  EXPECT_LE(m.at("cluster_mae_r"), cluster_max);
  EXPECT_GT(cell(r, "Error vs Embree", 1, "mae_max_channel_max_frame"), 0.0);  // the env map's
  EXPECT_TRUE(r.images.empty());  // no output directory: no images
}

TEST(ClusterReflectStudy, OcclusionCausesPartitionTheOcclusionErrors) {
  const Scene scene = load_scene("room-reflector");
  const Results r = study::run_cluster_reflect(scene, tiny_cluster_options(), {});
  double causes = 0.0;
  for (const char* name : {"occlusion_behind_near_plane_pct_avg", "occlusion_outside_image_pct_avg",
                           "occlusion_own_curved_reflector_pct_avg", "occlusion_hidden_in_image_pct_avg"})
    causes += r.metrics.at(name);
  EXPECT_NEAR(causes, r.metrics.at("occlusion_error_pct_avg"), 1e-9);
  EXPECT_GE(r.metrics.at("occlusion_error_pct_avg"), 0.0);
  EXPECT_LE(r.metrics.at("occlusion_error_pct_max"), 100.0);
}

TEST(ClusterReflectStudy, SameMetricsAndImagesForOneAndTwoThreads) {
  const Scene scene = load_scene("room-reflector");
  TempDir dir;
  Results runs[2];
  for (int threads : {1, 2}) {
    ThreadLimit limit(threads);
    runs[threads - 1] =
        study::run_cluster_reflect(scene, tiny_cluster_options(), {dir.path / std::to_string(threads)});
  }
  EXPECT_GT(expect_same_metrics(runs[0], runs[1]), 30u);
  EXPECT_EQ(runs[0].images.size(), 6u);
  expect_same_images(runs[0], runs[1], dir.path / "1", dir.path / "2");
}

// --method ssr is the cluster study with SSR beside it: its figures are added, the cluster
// method's and the comparison's stay as they were.
TEST(ClusterReflectStudy, SsrAddsItsFiguresAndChangesNoOther) {
  const Scene scene = load_scene("room-reflector");
  study::ClusterReflectOptions o = tiny_cluster_options();
  const Results plain = study::run_cluster_reflect(scene, o, {});
  o.ssr = true;
  const Results with_ssr = study::run_cluster_reflect(scene, o, {});
  auto timing = [](const std::string& name) {
    return name.find("ms") != std::string::npos || name.find("speedup") != std::string::npos;
  };
  for (const auto& [name, value] : plain.metrics) {
    const std::string& n = name;
    if (timing(n)) continue;
    ASSERT_TRUE(with_ssr.metrics.count(n)) << n;
    EXPECT_EQ(with_ssr.metrics.at(n), value) << n;
  }
  const auto& m = with_ssr.metrics;
  for (const char* name : {"ssr_mae_r", "boxprobe_mae_g", "ssr_fallback_pct_avg", "ssr_steps_per_ray_avg"})
    EXPECT_TRUE(m.count(name)) << name;
  EXPECT_GE(m.at("ssr_fallback_pct_avg"), 0.0);
  EXPECT_LE(m.at("ssr_fallback_pct_avg"), 100.0);
  EXPECT_GT(m.at("ssr_mae_r"), 0.0);
  EXPECT_EQ(with_ssr.tables.size(), plain.tables.size() + 1);
  EXPECT_EQ(with_ssr.tables.back().title.rfind("SSR with box-probe fallback", 0), 0u);
}

TEST(ClusterReflectStudy, BadOptionsNameTheFlag) {
  const Scene scene = load_scene("room-reflector");
  auto message = [&](const study::ClusterReflectOptions& o) -> std::string {
    try {
      study::run_cluster_reflect(scene, o, {});
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  study::ClusterReflectOptions o = tiny_cluster_options();
  o.width = kMaxImageSide + 1;
  EXPECT_NE(message(o).find("--width"), std::string::npos);
  o = tiny_cluster_options();
  o.cube_size = 0;
  EXPECT_NE(message(o).find("--cube-size"), std::string::npos);
  o = tiny_cluster_options();
  o.camera.path = "nope";
  EXPECT_NE(message(o).find("--path"), std::string::npos);
  o = tiny_cluster_options();
  o.compare = false;
  o.full_reference = true;
  EXPECT_NE(message(o).find("--full-reference"), std::string::npos);
  o = tiny_cluster_options();
  o.camera.path.clear();  // the scene camera
  try {
    study::validate(o, load_scene("maze"));  // no reflective object
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--scene"), std::string::npos) << e.what();
  }
}

}  // namespace proxima
