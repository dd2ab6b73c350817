// Radiance maps (phase 3): the visibility-map mapping never maps a pixel straddling the
// door frame's silhouette onto the wall behind, and never gives a texel the color of a
// photograph it is occluded in — both checked against Embree ray casts, and both shown to
// fail for the item-buffer baseline (so the checks can fail).
#include "proxima/gibr/radiance_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>

#include "proxima/core/image_io.h"
#include "proxima/core/rng.h"
#include "proxima/gibr/novel_view.h"
#include "proxima/gibr/photo_set.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/bsp_build.h"

namespace proxima::gibr {
namespace {

using namespace proxima::visibility;

// In room A, looking through the door (z 1.5..2.5, x 5..5.2) at room B's far wall, so the
// jamb at z = 1.5 is a silhouette against the wall behind.
Camera door_camera(int w, int h) { return look_at({3.2f, 1.3f, 2.4f}, {9.0f, 1.2f, 1.2f}, {0, 1, 0}, 40.0f, w, h); }

struct SubSamples {
  std::set<uint32_t> polygons;
  float t_min = INFINITY, t_max = 0.0f;
};

// 8 × 8 ray casts per pixel: the polygons each pixel square covers and their hit distances.
Image<SubSamples> sub_samples(const RayScene& rays, const ModelPolygons& model, const Camera& cam) {
  Image<SubSamples> out(cam.width, cam.height, 1);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
          const Ray r = ray_through(cam, vec2(float(x) + (float(i) + 0.5f) / 8.0f, float(y) + (float(j) + 0.5f) / 8.0f));
          const Hit h = rays.intersect(r);
          SubSamples& s = out.at(x, y);
          s.polygons.insert(h.valid() ? model.triangle_polygon[h.triangle] : kNone);
          if (h.valid()) s.t_min = std::min(s.t_min, h.t), s.t_max = std::max(s.t_max, h.t);
        }
  return out;
}

// The rooms model seen through the door at 64 × 48, with its 8 × 8 ray casts per pixel.
struct DoorView {
  Scene scene = make_vis_rooms();
  ModelPolygons model = extract_polygons(scene);
  WingedPair wp = build_winged_pair(model);
  RayScene rays{scene};
  Camera cam = door_camera(64, 48);
  Image<SubSamples> sub = sub_samples(rays, model, cam);
};

// A silhouette pixel: several surfaces with a depth jump (the jamb in front of the wall).
bool straddles(const SubSamples& s) { return s.polygons.size() >= 2 && s.t_max - s.t_min >= 0.5f; }

TEST(GibrMapping, DoorFrameSilhouettePixelIsNotMappedOntoTheWallBehind) {
  const DoorView door;
  const Scene& scene = door.scene;
  const ModelPolygons& model = door.model;
  const WingedPair& wp = door.wp;
  const RayScene& rays = door.rays;
  const Camera& cam = door.cam;
  const Image<SubSamples>& sub = door.sub;
  const ImageU32 vis = vismap_pixel_polygons(trace_visibility_map(wp, cam));
  const ImageU32 item = itembuffer_pixel_polygons(scene, model, cam);
  int straddling = 0, vis_mapped = 0, item_mapped_behind = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const SubSamples& s = sub.at(x, y);
      if (!straddles(s)) continue;
      ++straddling;
      vis_mapped += vis.at(x, y) != kNone;
      // The baseline maps it onto whatever its center sees, often the far wall.
      const Ray center = ray_through(cam, vec2(float(x) + 0.5f, float(y) + 0.5f));
      const Hit h = rays.intersect(center);
      item_mapped_behind += item.at(x, y) != kNone && h.valid() && h.t > s.t_min + 0.25f;
    }
  EXPECT_GT(straddling, 10);
  EXPECT_EQ(vis_mapped, 0);
  EXPECT_GT(item_mapped_behind, 0);

  // And on the radiance maps: no sample of this photograph comes from a pixel straddling a
  // silhouette; with --exclude-boundaries, every sample comes from a pixel wholly on the
  // sample's polygon (all 64 sub-samples).
  const ImageF photo = render_photo(make_photo_scene(scene), rays, cam, 2, 1);
  const std::vector<Camera> cams{cam};
  const std::vector<ImageF> photos{photo};
  for (bool all_boundaries : {false, true}) {
    const std::vector<ImageU32> labels{vismap_pixel_polygons(trace_visibility_map(wp, cam), all_boundaries)};
    const RadianceMaps maps = build_radiance_maps(model, 0.02, cams, photos, labels);
    size_t samples = 0, from_silhouette = 0, from_mixed = 0;
    for (uint32_t p = 0; p < maps.layers.size(); ++p)
      for (const SampleLayer& L : maps.layers[p])
        for (int j = L.y0; j < L.y0 + L.height; ++j)
          for (int i = L.x0; i < L.x0 + L.width; ++i) {
            // Exact-visible samples project into silhouette pixels by design; their colors'
            // sources are checked in ExactVisibleTexelsTakeColorOnlyFromPixelsWhollyOnTheirPolygon.
            if (!L.has(i, j) || L.rgba[size_t(j - L.y0) * size_t(L.width) + size_t(i - L.x0)] >> 24 != 0xFF) continue;
            ++samples;
            const auto q = project(cam, vec3(texel_center(maps.grids[p], i, j)));
            ASSERT_TRUE(q.has_value());
            const SubSamples& s = sub.at(std::clamp(int(q->pixel.x), 0, cam.width - 1),
                                         std::clamp(int(q->pixel.y), 0, cam.height - 1));
            from_mixed += s.polygons != std::set<uint32_t>{p};
            from_silhouette += straddles(s);
          }
    EXPECT_GT(samples, 1000u);
    EXPECT_EQ(from_silhouette, 0u);
    if (all_boundaries) {
      EXPECT_EQ(from_mixed, 0u);
    }
  }
}

TEST(GibrMapping, OccludedTexelNeverReceivesThatPhotographsColor) {
  const Scene scene = make_vis_rooms();
  const ModelPolygons model = extract_polygons(scene);
  const WingedPair wp = build_winged_pair(model);
  const RayScene rays(scene);
  const Scene textured = make_photo_scene(scene);
  PhotoPoseOptions po;
  po.count = 3;
  po.width = 48;
  po.height = 36;
  std::vector<Camera> cams = photo_poses(rays, scene.camera_paths.front(), po, 0.01f, 100.0f);
  cams.push_back(door_camera(48, 36));
  std::vector<ImageF> photos;
  std::vector<ImageU32> vis, item;
  for (const Camera& c : cams) {
    photos.push_back(render_photo(textured, rays, c, 1, 1));
    vis.push_back(vismap_pixel_polygons(trace_visibility_map(wp, c)));
    item.push_back(itembuffer_pixel_polygons(scene, model, c));
  }
  // A sample of photograph k at texel center x is occluded when the segment from k's eye to
  // x hits something before x (tolerance 1e-4 × model scale).
  auto occluded_samples = [&](const RadianceMaps& maps, size_t& total) {
    size_t bad = 0;
    total = 0;
    const float eps = float(1e-4 * model.scale);
    for (uint32_t p = 0; p < maps.layers.size(); ++p)
      for (const SampleLayer& L : maps.layers[p]) {
        const vec3 eye = maps.cameras[L.photo].position;
        for (int j = L.y0; j < L.y0 + L.height; ++j)
          for (int i = L.x0; i < L.x0 + L.width; ++i) {
            if (!L.has(i, j)) continue;
            ++total;
            const vec3 x(texel_center(maps.grids[p], i, j));
            const float d = glm::length(x - eye);
            bad += rays.occluded(Ray{eye, (x - eye) / d, 0.0f, d - eps});
          }
      }
    return bad;
  };
  size_t vis_total = 0, item_total = 0;
  const RadianceMaps vis_maps = build_radiance_maps(model, 0.02, cams, photos, vis);
  EXPECT_GT(vis_maps.stats.samples_extrapolated, 100u) << "the check should cover exact-visible texels in silhouette pixels";
  const size_t vis_bad = occluded_samples(vis_maps, vis_total);
  const size_t item_bad = occluded_samples(build_radiance_maps(model, 0.02, cams, photos, item), item_total);
  EXPECT_GT(vis_total, 10000u);
  EXPECT_EQ(vis_bad, 0u) << "of " << vis_total;
  EXPECT_GT(item_bad, 0u) << "the item-buffer baseline should map some occluded texels (of " << item_total << ")";

  // With unmixed silhouette pixels (photographs of 2 × 2 samples, so pixels are true mixes):
  // the unmixed colors go only to exactly visible texels too.
  std::vector<ImageF> photos2;
  std::vector<ImageU32> unmixed, unmixed_exact;
  std::vector<VisibilityMap> photo_maps;
  for (const Camera& c : cams) {
    photos2.push_back(render_photo(textured, rays, c, 2, 1));
    photo_maps.push_back(trace_visibility_map(wp, c));
    unmixed.push_back(unmix_silhouette_pixels(photo_maps.back(), vismap_pixel_polygons(photo_maps.back()), photos2.back(), 2));
    unmixed_exact.push_back(
        unmix_silhouette_pixels(photo_maps.back(), vismap_pixel_polygons(photo_maps.back(), false, false), photos2.back(), 2));
  }
  const RadianceMaps unmixed_maps = build_radiance_maps(model, 0.02, cams, photos2, unmixed);
  EXPECT_GT(unmixed_maps.stats.samples_unmixed, 100u) << "the check should cover unmixed samples";
  size_t unmixed_total = 0;
  EXPECT_EQ(occluded_samples(unmixed_maps, unmixed_total), 0u) << "of " << unmixed_total;
  // And with the exact texel-center test (the maps given, as build_gibr_model does).
  const RadianceMaps exact_maps = build_radiance_maps(model, 0.02, cams, photos2, unmixed_exact, photo_maps);
  EXPECT_GT(exact_maps.stats.samples_extrapolated + exact_maps.stats.samples_unmixed,
            unmixed_maps.stats.samples_extrapolated + unmixed_maps.stats.samples_unmixed);
  size_t exact_total = 0;
  EXPECT_EQ(occluded_samples(exact_maps, exact_total), 0u) << "of " << exact_total;
}

// The sub-pixel record fills texels seen only in pixels touching a silhouette, never with
// those pixels' colors: a synthetic photograph is white on pixels wholly on one side of a
// silhouette and black on pixels straddling one (8 × 8 ray casts), so a sample darker than
// white took color from a straddling pixel. The item buffer does (the check can fail); the
// exact-visible samples exist, and the mapping covers more texels than without the record.
TEST(GibrMapping, ExactVisibleTexelsTakeColorOnlyFromPixelsWhollyOnTheirPolygon) {
  const DoorView door;
  const Camera& cam = door.cam;
  const ModelPolygons& model = door.model;
  ImageF photo(cam.width, cam.height, 3, 1.0f);
  int straddling = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      if (!straddles(door.sub.at(x, y))) continue;
      ++straddling;
      for (int c = 0; c < 3; ++c) photo.at(x, y, c) = 0.0f;
    }
  ASSERT_GT(straddling, 10);
  const std::vector<Camera> cams{cam};
  const std::vector<ImageF> photos{photo};
  const VisibilityMap map = trace_visibility_map(door.wp, cam);
  struct Count {
    size_t samples = 0, extrapolated = 0, mixed = 0, dark = 0;
  };
  auto count = [&](const RadianceMaps& maps) {
    Count n;
    for (const auto& layers : maps.layers)
      for (const SampleLayer& L : layers)
        for (uint32_t t : L.rgba) {
          if ((t >> 24) == 0) continue;
          if ((t >> 24) == kMixed) {
            ++n.mixed;  // last resort for holes, the straddling pixel's color by design
            continue;
          }
          ++n.samples;
          n.extrapolated += (t >> 24) == kExtrapolated;
          n.dark += (t & 0xFFu) < 255u;
        }
    EXPECT_EQ(n.samples, maps.stats.samples);
    EXPECT_EQ(n.extrapolated, maps.stats.samples_extrapolated);
    EXPECT_EQ(n.mixed, maps.stats.samples_mixed);
    return n;
  };
  auto count_labels = [&](const ImageU32& labels) {
    return count(build_radiance_maps(model, 0.02, cams, photos, std::vector<ImageU32>{labels}));
  };
  const RadianceMaps exact_maps = build_radiance_maps(model, 0.02, cams, photos, std::vector<ImageU32>{vismap_pixel_polygons(map)});
  const Count exact = count(exact_maps);
  const Count whole = count_labels(vismap_pixel_polygons(map, false, false));
  const Count item = count_labels(itembuffer_pixel_polygons(door.scene, model, cam));
  EXPECT_GT(exact.extrapolated, 50u);
  EXPECT_GT(exact.mixed, 0u) << "the novel-view check below should meet last-resort samples";
  EXPECT_EQ(exact.dark, 0u) << "of " << exact.samples << " samples, " << exact.extrapolated << " exact-visible";
  EXPECT_EQ(whole.extrapolated, 0u);
  EXPECT_EQ(whole.mixed, 0u);
  EXPECT_EQ(whole.dark, 0u);
  // A novel view blends only clean samples: every pixel not flagged unseen is white.
  const NovelView nv = render_novel_view(door.scene, model, exact_maps, cam);
  size_t seen = 0, seen_dark = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      if (nv.unseen.at(x, y)) continue;  // (the rooms are closed: no background pixels)
      ++seen;
      seen_dark += nv.color.at(x, y, 0) < 0.99f;
    }
  EXPECT_GT(seen, size_t(cam.width * cam.height / 2));
  EXPECT_EQ(seen_dark, 0u);
  EXPECT_EQ(exact.samples, whole.samples + exact.extrapolated);
  EXPECT_GT(item.dark, 50u) << "the item buffer maps straddling pixels' colors";
}

// Unmixing: a photograph whose polygons are flat colored (each of the 2 × 2 samples of a
// pixel the color of the polygon a ray cast there hits, the background black), so every
// pixel touching the door jamb's silhouette is an exact mix of the jamb and the wall behind.
// Every unmixed pixel is unmixed for the polygon that the ray-cast oracle finds in at least
// half of its samples, and recovers that polygon's color to within sRGB rounding — while
// the raw mixed colors are far from it (the check can fail); the exact-visible texel samples
// colored from unmixed pixels carry it too.
TEST(GibrMapping, UnmixedSilhouettePixelsRecoverTheirPolygonsFlatColor) {
  const DoorView door;
  const Camera& cam = door.cam;
  const ModelPolygons& model = door.model;
  const size_t np = model.polygons.size();
  std::vector<vec3> flat(np);
  for (size_t p = 0; p < np; ++p)  // distinct colors in [0.1, 0.9]
    flat[p] = vec3(0.1f + 0.8f * float((p * 37) % 11) / 10.0f, 0.1f + 0.8f * float((p * 53) % 7) / 6.0f,
                   0.1f + 0.8f * float((p * 17) % 5) / 4.0f);
  const int s = 2;
  ImageF photo(cam.width, cam.height, 3, 0.0f);
  Image<std::array<uint32_t, 4>> hits(cam.width, cam.height, 1);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      vec3 c(0.0f);
      for (int k = 0; k < s * s; ++k) {
        const vec2 at(float(x) + (float(k % s) + 0.5f) / float(s), float(y) + (float(k / s) + 0.5f) / float(s));
        const Hit h = door.rays.intersect(ray_through(cam, at));
        const uint32_t q = h.valid() ? model.triangle_polygon[h.triangle] : kNone;
        hits.at(x, y)[size_t(k)] = q;
        if (q != kNone) c += flat[q] / float(s * s);
      }
      for (int ch = 0; ch < 3; ++ch) photo.at(x, y, ch) = c[ch];
    }
  const VisibilityMap map = trace_visibility_map(door.wp, cam);
  const ImageU32 labels = unmix_silhouette_pixels(map, vismap_pixel_polygons(map), photo, s);
  ASSERT_EQ(labels.channels(), kRecordChannels + 2);
  // sRGB 8-bit distance (0–255) between a packed color and a linear one.
  auto srgb_error = [](uint32_t packed, const vec3& linear) {
    const vec3 q = unpack_srgb8(packed);
    float e = 0.0f;
    for (int ch = 0; ch < 3; ++ch) e = std::max(e, std::abs(linear_to_srgb(q[ch]) - linear_to_srgb(linear[ch])) * 255.0f);
    return e;
  };
  size_t unmixed = 0, truly_mixed = 0, oracle_bad = 0, color_bad = 0;
  float worst = 0.0f;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const uint32_t p = labels.at(x, y, kRecordChannels);
      if (p == kNone) continue;
      ++unmixed;
      const auto& h = hits.at(x, y);
      oracle_bad += 2 * std::count(h.begin(), h.end(), p) < s * s;
      const vec3 raw(photo.at(x, y, 0), photo.at(x, y, 1), photo.at(x, y, 2));
      truly_mixed += srgb_error(pack_srgb8(raw), flat[p]) > 20.0f;
      const float e = srgb_error(labels.at(x, y, kRecordChannels + 1), flat[p]);
      worst = std::max(worst, e);
      color_bad += e > 1.0f;
    }
  EXPECT_GT(truly_mixed, 10u) << "of " << unmixed << " unmixed pixels";
  EXPECT_EQ(oracle_bad, 0u) << "of " << unmixed;
  EXPECT_EQ(color_bad, 0u) << "of " << unmixed << " unmixed pixels; worst " << worst << " / 255";

  const RadianceMaps maps = build_radiance_maps(model, 0.02, std::vector<Camera>{cam}, std::vector<ImageF>{photo},
                                                std::vector<ImageU32>{labels});
  size_t samples = 0, samples_bad = 0;
  for (uint32_t p = 0; p < np; ++p)
    for (const SampleLayer& L : maps.layers[p])
      for (uint32_t t : L.rgba) {
        if ((t >> 24) != kUnmixed) continue;
        ++samples;
        samples_bad += srgb_error(t, flat[p]) > 1.0f;
      }
  EXPECT_EQ(samples, maps.stats.samples_unmixed);
  EXPECT_GT(samples, 50u);
  EXPECT_EQ(samples_bad, 0u) << "of " << samples;
}

// The exact texel-center test (the visibility map's regions given to build_radiance_maps):
// in the pixels not mapped onto its polygon (touching a silhouette, or on a crease and mapped
// onto the other polygon), every texel that the ray-cast oracle sees clearly —
// rays through its projection and through points 0.01 px around it all hit its polygon — gets
// a sample, none of them occluded; the 8 × 8 sub-cell record misses some (its strip of
// sub-cells touching a silhouette), so the check can fail.
TEST(GibrMapping, ExactTexelCenterTestSamplesEveryClearlyVisibleTexelBesideRegionBoundaries) {
  const DoorView door;
  const Camera& cam = door.cam;
  const ModelPolygons& model = door.model;
  const ImageF photo = render_photo(make_photo_scene(door.scene), door.rays, cam, 2, 1);
  const VisibilityMap map = trace_visibility_map(door.wp, cam);
  const std::vector<Camera> cams{cam};
  const std::vector<ImageF> photos{photo};
  const ImageU32 whole = vismap_pixel_polygons(map, false, false);
  const RadianceMaps exact = build_radiance_maps(model, 0.01, cams, photos, std::vector<ImageU32>{whole},
                                                 std::vector<VisibilityMap>{map});
  const RadianceMaps record = build_radiance_maps(model, 0.01, cams, photos, std::vector<ImageU32>{vismap_pixel_polygons(map)});
  auto sampled = [](const RadianceMaps& m, uint32_t p, int i, int j) {
    for (const SampleLayer& L : m.layers[p])
      if (L.has(i, j)) return true;
    return false;
  };
  const vec3 eye = cam.position;
  const float eps = float(1e-4 * model.scale);
  auto sees = [&](const vec2& at, uint32_t p) {
    const Hit h = door.rays.intersect(ray_through(cam, at));
    return h.valid() && model.triangle_polygon[h.triangle] == p;
  };
  size_t clear = 0, exact_missed = 0, record_missed = 0, exact_samples = 0, occluded = 0;
  for (uint32_t p = 0; p < model.polygons.size(); ++p) {
    const TexelGrid& g = exact.grids[p];
    for (int j = 0; j < g.height; ++j)
      for (int i = 0; i < g.width; ++i) {
        const vec3 x(texel_center(g, i, j));
        const auto q = project(cam, x);
        if (!q || !(q->pixel.x >= 0.0f && q->pixel.y >= 0.0f && q->pixel.x < float(cam.width) &&
                    q->pixel.y < float(cam.height)))
          continue;
        if (whole.at(int(q->pixel.x), int(q->pixel.y)) == p) continue;  // pixels not mapped onto p only
        if (sampled(exact, p, i, j)) {
          ++exact_samples;
          const float d = glm::length(x - eye);
          occluded += door.rays.occluded(Ray{eye, (x - eye) / d, 0.0f, d - eps});
        }
        bool clearly = sees(q->pixel, p);
        for (int k = 0; k < 4 && clearly; ++k)
          clearly = sees(q->pixel + 0.01f * vec2(k == 0 ? 1 : k == 1 ? -1 : 0, k == 2 ? 1 : k == 3 ? -1 : 0), p);
        if (!clearly) continue;
        ++clear;
        exact_missed += !sampled(exact, p, i, j);
        record_missed += !sampled(record, p, i, j);
      }
  }
  EXPECT_GT(clear, 500u);
  EXPECT_EQ(exact_missed, 0u) << "of " << clear << " clearly visible texels in pixels not mapped onto their polygon";
  EXPECT_GT(record_missed, 10u) << "the sub-cell record should miss some (of " << clear << ")";
  EXPECT_EQ(occluded, 0u) << "of " << exact_samples;
  EXPECT_GE(exact.stats.samples, record.stats.samples);
}

// fill_reach against brute force: per block, the least chessboard distance from its texels to a
// sample of each threshold (capped at 255), on sparse random layers of odd sizes — one wider
// than 255 texels with a single sample, so the cap and the blocks' far values are exercised.
TEST(GibrMapping, ReachIsTheLeastChessboardDistanceToASamplePerBlock) {
  Pcg32 rng(7);
  for (int trial = 0; trial < 6; ++trial) {
    SampleLayer L;
    L.width = trial == 5 ? 300 : 5 + int(rng.next_below(40));
    L.height = trial == 5 ? 3 : 3 + int(rng.next_below(30));
    L.rgba.assign(size_t(L.width) * size_t(L.height), 0u);
    const uint32_t alphas[4] = {0xFF, kUnmixed, kExtrapolated, kMixed};
    const int n = trial == 5 ? 1 : 1 + int(rng.next_below(6));
    for (int s = 0; s < n; ++s) {
      const uint32_t a = trial == 5 ? 0xFF : alphas[rng.next_below(4)];
      L.rgba[rng.next_below(uint32_t(L.rgba.size()))] = a << 24;
      L.mixed += a == kMixed;
    }
    fill_reach(L);
    for (uint32_t min_alpha : {kExtrapolated, kMixed}) {
      const std::vector<uint8_t>& reach = min_alpha == kMixed ? L.reach_mixed : L.reach;
      if (min_alpha == kMixed && L.mixed == 0) {
        EXPECT_TRUE(reach.empty());
        continue;
      }
      const int bw = L.reach_columns(), bh = (L.height + kReachBlock - 1) / kReachBlock;
      ASSERT_EQ(reach.size(), size_t(bw) * size_t(bh));
      for (int bj = 0; bj < bh; ++bj)
        for (int bi = 0; bi < bw; ++bi) {
          int best = 255;
          for (int j = bj * kReachBlock; j < std::min(L.height, (bj + 1) * kReachBlock); ++j)
            for (int i = bi * kReachBlock; i < std::min(L.width, (bi + 1) * kReachBlock); ++i)
              for (int t = 0; t < L.height * L.width; ++t)
                if ((L.rgba[size_t(t)] >> 24) >= min_alpha)
                  best = std::min(best, std::max(std::abs(t % L.width - i), std::abs(t / L.width - j)));
          EXPECT_EQ(int(reach[size_t(bj) * size_t(bw) + size_t(bi)]), best)
              << "trial " << trial << ", block " << bi << "," << bj << ", alpha ≥ " << min_alpha;
        }
    }
  }
}
}  // namespace
}  // namespace proxima::gibr
