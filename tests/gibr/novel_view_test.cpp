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

// Five 80 × 60 photographs of textured rooms with k × k samples per pixel, and their
// visibility-map radiance maps (1 cm texels).
struct Rig {
  Scene scene;
  ModelPolygons model;
  std::vector<Camera> cams;
  std::vector<ImageF> photos;
  RadianceMaps maps;
};

Rig make_rig(int photo_supersample) {
  Rig r;
  const Scene model_scene = make_vis_rooms();
  r.model = extract_polygons(model_scene);
  const WingedPair wp = build_winged_pair(r.model);
  PhotoSceneOptions so;
  so.period = 2.0;
  so.texture_size = 16;  // detail of 12.5 cm: smooth at the 1 cm texels
  r.scene = make_photo_scene(model_scene, so);
  const RayScene rays(r.scene);
  PhotoPoseOptions po;
  po.count = 5;
  po.width = 80;
  po.height = 60;
  r.cams = photo_poses(rays, r.scene.camera_paths.front(), po, 0.01f, 100.0f);
  std::vector<ImageU32> labels;
  for (const Camera& c : r.cams) {
    r.photos.push_back(render_photo(r.scene, rays, c, photo_supersample, 1));
    labels.push_back(vismap_pixel_polygons(trace_visibility_map(wp, c)));
  }
  r.maps = build_radiance_maps(r.model, 0.01, r.cams, r.photos, labels);
  return r;
}

// Novel views at the poses of photographs 0 and 3 reproduce them at ≥ 40 dB on seen pixels
// (which must be > 80 % of the pixels with surface).
void expect_reproduces_photos(const Rig& r, const NovelViewOptions& o) {
  for (size_t k : {size_t(0), size_t(3)}) {
    const NovelView nv = render_novel_view(r.scene, r.model, r.maps, r.cams[k], o);
    ImageU8 seen(r.cams[k].width, r.cams[k].height, 1, 0);
    size_t count = 0;
    for (int y = 0; y < r.cams[k].height; ++y)
      for (int x = 0; x < r.cams[k].width; ++x) count += seen.at(x, y) = !nv.unseen.at(x, y);
    EXPECT_GT(double(count), 0.8 * double(nv.covered)) << "photo " << k;
    const ImageError e = compare_images(nv.color, r.photos[k], &seen);
    EXPECT_GE(e.psnr_db, 40.0) << "photo " << k << ", MAE " << e.mae_avg << ", novel-view samples " << o.supersample;
  }
}

TEST(GibrNovelView, AtAPhotographsPoseReproducesIt) {
  // Pixel-center samples: a novel view samples the surface at pixel centers too, so the
  // photograph is reproducible (a supersampled photo's silhouette pixels mix surfaces).
  expect_reproduces_photos(make_rig(1), {});
}

// Multisampled novel view (2 × 2, the photograph's sample positions) at a photograph's pose:
// interior pixels shaded once reproduce the supersampled photograph, and the pixels shaded
// per sample (silhouettes, polygon boundaries) do not spoil it. (Shading every sample would
// filter the already pixel-filtered photograph twice: 39 / 37 dB.)
TEST(GibrNovelView, SupersampledAtAPhotographsPoseReproducesASupersampledPhotograph) {
  NovelViewOptions ss2;
  ss2.supersample = 2;
  expect_reproduces_photos(make_rig(2), ss2);
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
