// Novel views (phase 4): a view from exactly a photograph's pose reproduces that photograph
// on the pixels whose surface some photograph saw, at one sample per pixel and supersampled
// like a supersampled photograph.
#include "proxima/gibr/novel_view.h"

#include <gtest/gtest.h>

#include "proxima/core/error.h"
#include "proxima/eval/image_error.h"
#include "proxima/gibr/photo_set.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/bsp_build.h"

namespace proxima::gibr {
namespace {

using namespace proxima::visibility;

TEST(GibrNovelView, AtAPhotographsPoseReproducesIt) {
  const Scene model_scene = make_vis_rooms();
  const ModelPolygons model = extract_polygons(model_scene);
  const WingedPair wp = build_winged_pair(model);
  PhotoSceneOptions so;
  so.period = 2.0;
  so.texture_size = 16;  // detail of 12.5 cm: smooth at the 1 cm texels
  const Scene scene = make_photo_scene(model_scene, so);
  const RayScene rays(scene);
  PhotoPoseOptions po;
  po.count = 5;
  po.width = 80;
  po.height = 60;
  const std::vector<Camera> cams = photo_poses(rays, scene.camera_paths.front(), po, 0.01f, 100.0f);
  std::vector<ImageF> photos;
  std::vector<ImageU32> labels;
  for (const Camera& c : cams) {
    // Pixel-center samples: a novel view samples the surface at pixel centers too, so the
    // photograph is reproducible (a supersampled photo's silhouette pixels mix surfaces).
    photos.push_back(render_photo(scene, rays, c, 1, 1));
    labels.push_back(vismap_pixel_polygons(trace_visibility_map(wp, c)));
  }
  const RadianceMaps maps = build_radiance_maps(model, 0.01, cams, photos, labels);
  for (size_t k : {size_t(0), size_t(3)}) {
    const NovelView nv = render_novel_view(scene, model, maps, cams[k]);
    ImageU8 seen(cams[k].width, cams[k].height, 1, 0);
    size_t count = 0;
    for (int y = 0; y < cams[k].height; ++y)
      for (int x = 0; x < cams[k].width; ++x) count += seen.at(x, y) = !nv.unseen.at(x, y);
    EXPECT_GT(double(count), 0.8 * double(nv.covered)) << "photo " << k;
    const ImageError e = compare_images(nv.color, photos[k], &seen);
    EXPECT_GE(e.psnr_db, 40.0) << "photo " << k << ", MAE " << e.mae_avg;
  }
}

// Multisampled novel view (2 × 2, the photograph's sample positions) at a photograph's pose:
// interior pixels shaded once reproduce the supersampled photograph, and the pixels shaded
// per sample (silhouettes, polygon boundaries) do not spoil it.
TEST(GibrNovelView, SupersampledAtAPhotographsPoseReproducesASupersampledPhotograph) {
  const Scene model_scene = make_vis_rooms();
  const ModelPolygons model = extract_polygons(model_scene);
  const WingedPair wp = build_winged_pair(model);
  PhotoSceneOptions so;
  so.period = 2.0;
  so.texture_size = 16;
  const Scene scene = make_photo_scene(model_scene, so);
  const RayScene rays(scene);
  PhotoPoseOptions po;
  po.count = 5;
  po.width = 80;
  po.height = 60;
  const std::vector<Camera> cams = photo_poses(rays, scene.camera_paths.front(), po, 0.01f, 100.0f);
  std::vector<ImageF> photos;
  std::vector<ImageU32> labels;
  for (const Camera& c : cams) {
    photos.push_back(render_photo(scene, rays, c, 2, 1));
    labels.push_back(vismap_pixel_polygons(trace_visibility_map(wp, c)));
  }
  const RadianceMaps maps = build_radiance_maps(model, 0.01, cams, photos, labels);
  NovelViewOptions ss2;
  ss2.supersample = 2;
  for (size_t k : {size_t(0), size_t(3)}) {
    const NovelView nv = render_novel_view(scene, model, maps, cams[k], ss2);
    const NovelView n1 = render_novel_view(scene, model, maps, cams[k]);
    ImageU8 seen(cams[k].width, cams[k].height, 1, 0);
    size_t count = 0;
    for (int y = 0; y < cams[k].height; ++y)
      for (int x = 0; x < cams[k].width; ++x) count += seen.at(x, y) = !nv.unseen.at(x, y);
    EXPECT_GT(double(count), 0.8 * double(nv.covered)) << "photo " << k;
    const ImageError e = compare_images(nv.color, photos[k], &seen);
    // Shading every sample would filter the (already pixel-filtered) photograph twice.
    const ImageError e1 = compare_images(n1.color, photos[k], &seen);
    EXPECT_GE(e.psnr_db, 40.0) << "photo " << k << ", MAE " << e.mae_avg << " (one sample per pixel: " << e1.psnr_db << ")";
  }
}

TEST(GibrNovelView, SupersampleOutsideOneToEightIsAnInputError) {
  const Scene scene = make_vis_rooms();
  const ModelPolygons model = extract_polygons(scene);
  const RadianceMaps maps{make_texel_grids(model, 0.1), std::vector<std::vector<SampleLayer>>(model.polygons.size()), {}, {}};
  const Camera cam = look_at({0, 1, 0}, {0, 1, -1}, {0, 1, 0}, 60, 16, 12);
  for (int s : {0, 9}) {
    NovelViewOptions o;
    o.supersample = s;
    EXPECT_THROW(render_novel_view(scene, model, maps, cam, o), InputError) << s;
  }
}

}  // namespace
}  // namespace proxima::gibr
