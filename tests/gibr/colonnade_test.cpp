// The colonnade model (thin columns and a railing in front of a textured wall) and two-pass
// unmixing, which gives thin occluders' pixels their own colors where no pixel lies wholly on
// them.
#include <gtest/gtest.h>

#include <algorithm>

#include "proxima/core/image_io.h"
#include "proxima/gibr/gibr_model.h"
#include "proxima/gibr/radiance_map.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/polygons.h"
#include "scene_checks.h"

namespace proxima::gibr {
namespace {

using namespace proxima::visibility;

TEST(GibrColonnade, PolygonsPathAndEveryPhotographsMapPassesItsSelfCheck) {
  EXPECT_GT(check_gibr_test_model(make_vis_colonnade(), 57), 20.0)
      << "thin occluders: many silhouette edges per photograph";
}

// A flat-colored photograph (each of the s × s samples of a pixel the color of the polygon a
// ray cast there hits) of the columns at a resolution where they are 2–4 px wide: two-pass
// unmixing unmixes more pixels than one pass, and every pixel it unmixes recovers the color
// of the polygon the ray-cast oracle finds in at least half of its samples.
TEST(GibrColonnade, TwoPassUnmixingRecoversThinOccludersFlatColors) {
  const Scene scene = make_vis_colonnade();
  const ModelPolygons model = extract_polygons(scene);
  const WingedPair wp = build_winged_pair(model);
  const RayScene rays(scene);
  const Camera cam = look_at({4.0f, 1.5f, 3.4f}, {4.0f, 1.2f, 0.0f}, {0, 1, 0}, 65.0f, 96, 72, 0.01f, 100.0f);
  const size_t np = model.polygons.size();
  std::vector<vec3> flat(np);
  for (size_t p = 0; p < np; ++p)
    flat[p] = vec3(0.1f + 0.8f * float((p * 37) % 11) / 10.0f, 0.1f + 0.8f * float((p * 53) % 7) / 6.0f,
                   0.1f + 0.8f * float((p * 17) % 5) / 4.0f);
  const int s = 2;
  ImageF photo(cam.width, cam.height, 3, 0.0f);
  std::vector<std::vector<uint32_t>> hits(size_t(cam.width * cam.height));
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      vec3 c(0.0f);
      for (int k = 0; k < s * s; ++k) {
        const vec2 at(float(x) + (float(k % s) + 0.5f) / float(s), float(y) + (float(k / s) + 0.5f) / float(s));
        const Hit h = rays.intersect(ray_through(cam, at));
        const uint32_t q = h.valid() ? model.triangle_polygon[h.triangle] : kNone;
        hits[size_t(y * cam.width + x)].push_back(q);
        if (q != kNone) c += flat[q] / float(s * s);
      }
      for (int ch = 0; ch < 3; ++ch) photo.at(x, y, ch) = c[ch];
    }
  const VisibilityMap map = trace_visibility_map(wp, cam);
  const ImageU32 labels = vismap_pixel_polygons(map, false, false);
  const ImageU32 one = unmix_silhouette_pixels(map, labels, photo, s, false, false);
  const ImageU32 two = unmix_silhouette_pixels(map, labels, photo, s, false, true);
  const int uc = unmix_channel(two);
  ASSERT_EQ(uc, 1);
  size_t n1 = 0, n2 = 0, oracle_bad = 0, color_bad = 0;
  float worst = 0.0f;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      n1 += one.at(x, y, uc) != kNone;
      const uint32_t p = two.at(x, y, uc);
      if (p == kNone) continue;
      ++n2;
      const auto& h = hits[size_t(y * cam.width + x)];
      oracle_bad += 2 * std::count(h.begin(), h.end(), p) < s * s;
      const vec3 q = unpack_srgb8(two.at(x, y, uc + 1));
      float e = 0.0f;
      for (int ch = 0; ch < 3; ++ch) e = std::max(e, std::abs(linear_to_srgb(q[ch]) - linear_to_srgb(flat[p][ch])) * 255.0f);
      worst = std::max(worst, e);
      color_bad += e > 2.0f;
    }
  EXPECT_GT(n2, n1 + 10) << "one pass " << n1 << ", two passes " << n2;
  EXPECT_EQ(oracle_bad, 0u) << "of " << n2;
  EXPECT_EQ(color_bad, 0u) << "of " << n2 << "; worst " << worst << " / 255";
}

}  // namespace
}  // namespace proxima::gibr
