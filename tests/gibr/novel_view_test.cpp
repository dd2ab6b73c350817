// Novel views (phase 4): a view from exactly a photograph's pose reproduces that photograph
// on the pixels whose surface some photograph saw, at one sample per pixel and supersampled
// like a supersampled photograph.
#include "proxima/gibr/novel_view.h"

#include <gtest/gtest.h>

#include <cstring>
#include <span>

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

// The fast path (one scan for direct and exact-visible samples, memoized hole fill over ring
// cells) gives the plain path's bits, at 1 and 2 × 2 samples per pixel, on views away from
// the photographs where many pixels are holes (most filled, some left black).
template <typename T>
bool same_bits(std::span<const T> a, std::span<const T> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size_bytes()) == 0;
}

TEST(GibrNovelView, FastPathGivesThePlainPathsBits) {
  const Rig r = make_rig(1);
  size_t holes = 0, filled = 0;
  // Reused by the fast renders (view 1 finds view 0's raster of the same size in it), fresh
  // for the plain ones.
  NovelViewScratch scratch;
  for (int s : {1, 2})
    for (int v = 0; v < 2; ++v) {
      const Camera& c = r.cams[size_t(v) * 2];
      // Turned around (and, for v = 1, wider): surfaces the five photographs hardly saw.
      const Camera cam = look_at(c.position, c.position - camera_forward(c) + 0.3f * camera_right(c), {0, 1, 0},
                                 v == 0 ? 60.0f : 90.0f, 96, 72, c.near, c.far);
      NovelViewOptions fast, plain;
      fast.supersample = plain.supersample = s;
      fast.hole_radius = plain.hole_radius = v == 0 ? 32 : 3;  // the reach's early exit fails some searches
      fast.k = plain.k = s == 1 ? 1 : 3;  // k = 1: exact-visible-only pixels are a larger share
      plain.fast = false;
      const NovelView a = render_novel_view(r.scene, r.model, r.maps, cam, fast, &scratch);
      const NovelView b = render_novel_view(r.scene, r.model, r.maps, cam, plain);
      EXPECT_TRUE(same_bits(a.color.data(), b.color.data())) << "view " << v << ", " << s << "×" << s;
      EXPECT_TRUE(same_bits(a.unseen.data(), b.unseen.data())) << "view " << v << ", " << s << "×" << s;
      EXPECT_EQ(a.holes, b.holes);
      EXPECT_EQ(a.holes_filled, b.holes_filled);
      EXPECT_EQ(a.covered, b.covered);
      holes += a.holes;
      filled += a.holes_filled;
    }
  EXPECT_GT(holes, 100u);  // the hole fill is exercised
  EXPECT_GT(filled, 0u);
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
