// build_gibr_model (phases 1–3 in one call): the same radiance maps as running the phases by
// hand, the baseline's maps only on request, and bad options rejected naming the flag.
#include "proxima/gibr/gibr_model.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "../test_util.h"
#include "proxima/core/rng.h"
#include "proxima/gibr/photo_set.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/scene/camera_select.h"

namespace proxima::gibr {
namespace {

using namespace proxima::visibility;

GibrModelOptions tiny() {
  GibrModelOptions o;
  o.photos = 3;
  o.photo_width = 40;
  o.photo_height = 30;
  o.supersample = 1;
  o.seed = 7;
  return o;
}

TEST(GibrModel, SameMapsAsThePhasesByHand) {
  const Scene rooms = make_vis_rooms();
  const GibrModel g = build_gibr_model(rooms, tiny());
  ASSERT_EQ(g.cameras.size(), 3u);
  ASSERT_EQ(g.photos.size(), 3u);
  EXPECT_EQ(g.texel, gibr_scene_defaults("rooms", 1.0).texel);
  EXPECT_TRUE(g.item_maps.grids.empty());  // not requested
  EXPECT_GT(g.maps.stats.samples, 0u);

  // By hand, as `proxima gibr` did before the move.
  const ModelPolygons model = extract_polygons(rooms);
  PhotoSceneOptions pso;
  pso.period = gibr_scene_defaults("rooms", model.scale).period;
  pso.seed = 7;
  const Scene scene = make_photo_scene(rooms, pso);
  const RayScene rays(scene);
  PhotoPoseOptions ppo;
  ppo.count = 3;
  ppo.width = 40;
  ppo.height = 30;
  ppo.seed = 7;
  const float far = scene_far_plane(scene);
  const std::vector<Camera> cams = photo_poses(rays, rooms.camera_paths.front(), ppo, 0.01f, far);
  const WingedPair wp = build_winged_pair(model);
  std::vector<ImageF> photos;
  std::vector<ImageU32> labels;
  std::vector<VisibilityMap> vis_maps;
  for (size_t i = 0; i < cams.size(); ++i) {
    photos.push_back(render_photo(scene, rays, cams[i], 1, derive_seed(7, i, 1)));
    vis_maps.push_back(trace_visibility_map(wp, cams[i]));
    labels.push_back(unmix_silhouette_pixels(vis_maps.back(), vismap_pixel_polygons(vis_maps.back(), false, false),
                                             photos.back(), 1));
    EXPECT_TRUE(photos.back() == g.photos[i]) << i;
  }
  const RadianceMaps maps = build_radiance_maps(model, g.texel, cams, photos, labels, vis_maps);
  ASSERT_EQ(maps.layers.size(), g.maps.layers.size());
  for (size_t p = 0; p < maps.layers.size(); ++p) {
    ASSERT_EQ(maps.layers[p].size(), g.maps.layers[p].size()) << p;
    for (size_t l = 0; l < maps.layers[p].size(); ++l) EXPECT_EQ(maps.layers[p][l].rgba, g.maps.layers[p][l].rgba);
  }

  GibrModelOptions both = tiny();
  both.item_buffer = true;
  const GibrModel h = build_gibr_model(rooms, both);
  EXPECT_EQ(h.item_maps.grids.size(), model.polygons.size());
  EXPECT_GT(h.item_maps.stats.samples, 0u);
}

TEST(GibrModel, BadOptionsNameTheFlag) {
  const Scene rooms = make_vis_rooms();
  auto err = [&](auto edit) {
    GibrModelOptions o = tiny();
    edit(o);
    return error_of([&] { (void)build_gibr_model(rooms, o); });
  };
  EXPECT_NE(err([](auto& o) { o.photos = 0; }).find("--photos"), std::string::npos);
  EXPECT_NE(err([](auto& o) { o.supersample = 9; }).find("--supersample"), std::string::npos);
  EXPECT_NE(err([](auto& o) { o.texel = -1.0; }).find("--texel"), std::string::npos);
  EXPECT_NE(err([](auto& o) { o.texel = 1e-6; }).find("--texel"), std::string::npos);  // too many texels
  EXPECT_NE(err([](auto& o) { o.photo_width = 0; }).find("--photo-width"), std::string::npos);
  Scene no_path = rooms;
  no_path.camera_paths.clear();
  EXPECT_NE(error_of([&] { (void)build_gibr_model(no_path, tiny()); }).find("no camera path"), std::string::npos);
}

}  // namespace
}  // namespace proxima::gibr
