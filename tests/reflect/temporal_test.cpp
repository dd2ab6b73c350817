// Temporal reuse of reflections: exact reuse for an unchanged camera, the best
// match against the analytic mirror correspondence, temporal vs direct reprojection on a
// planar mirror, disocclusion flags, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/eval/image_error.h"
#include "proxima/reflect/temporal_reuse.h"
#include "proxima/scene/procedural.h"
#include "reflect_test_scenes.h"
#include "reflect/wave_texture.h"

namespace proxima {

namespace {

using reflect_test::add_diffuse;
using reflect_test::add_quad;

// A 4 × 4 m floor mirror (y = 0, facing +Y), a smoothly textured 8 × 6 m wall behind it
// (z = −2, facing +Z), a point light; optionally a small diffuse box floating between the
// camera and the mirror (an occluder whose shadow on the key view disoccludes).
Scene floor_mirror(bool occluder) {
  Scene s;
  s.name = "floor-mirror";
  const uint32_t wall_mat = add_waves_wall_material(s);
  const uint32_t mirror_mat = add_diffuse(s, vec3(0.5f), 1.0f);
  add_quad(s, vec3(-2, 0, -2), vec3(0, 0, 4), vec3(4, 0, 0), mirror_mat, "mirror");
  add_quad(s, vec3(-4, -1, -2), vec3(8, 0, 0), vec3(0, 6, 0), wall_mat, "wall");
  if (occluder) {
    Mesh box = make_box(vec3(0.3f));
    for (vec3& p : box.positions) p += vec3(0.0f, 0.5f, 0.9f);
    add_object(s, box, "box", add_diffuse(s, vec3(0.9f, 0.3f, 0.1f)));
  }
  s.point_lights.push_back({vec3(0.0f, 3.0f, 1.0f), vec3(12.0f)});
  s.ambient = vec3(0.1f);
  return s;
}

constexpr int kSize = 96;
Camera eye_at(vec3 eye) { return look_at(eye, vec3(0.0f, 0.0f, -0.3f), vec3(0, 1, 0), 50.0f, kSize, kSize, 0.01f, 100.0f); }
const vec3 kKeyEye(0.0f, 1.5f, 3.0f);
const vec3 kMove(0.12f, 0.05f, -0.06f);  // the camera translation of the new frame

ReflectionFrame frame_at(const Scene& scene, vec3 eye) {
  ReflectionOptions o;
  o.supersample = 1;
  return prepare_reflection_frame(scene, eye_at(eye), o);
}

ImageU8 mask_of(const ReflectionFrame& frame, const std::vector<uint8_t>& keep) {
  ImageU8 mask(frame.camera.width, frame.camera.height, 1, 0);
  for (size_t i = 0; i < frame.sample_count(); ++i)
    if (keep[i]) mask.data()[frame.pixel[i]] = 1;
  return mask;
}

}  // namespace

TEST(TemporalReflections, UnchangedCameraReproducesTheKeyFrameAndRecomputesNothing) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  const ReflectionFrame frame = frame_at(scene, kKeyEye);
  ASSERT_GT(frame.sample_count(), 2000u);
  TemporalState state;
  TemporalFrameStats key_stats, stats;
  const std::vector<vec3> key = temporal_reflections(scene, rays, frame, state, {}, &key_stats);
  EXPECT_TRUE(key_stats.key);
  const std::vector<vec3> again = temporal_reflections(scene, rays, frame, state, {}, &stats);
  EXPECT_FALSE(stats.key);
  EXPECT_EQ(stats.recomputed, 0u);
  EXPECT_EQ(stats.invalid_offsets, 0u);
  EXPECT_FALSE(state.need_key);
  ASSERT_EQ(again.size(), key.size());
  float worst = 0.0f;
  for (size_t i = 0; i < key.size(); ++i)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(again[i][c] - key[i][c]));
  // Only float rounding (offsets of ~1e-7 px from the parabola fit and the projection).
  EXPECT_LT(worst, 1e-5f);
}

TEST(TemporalReflections, BestMatchIsTheAnalyticMirrorCorrespondence) {
  const Scene scene = floor_mirror(false);
  RayScene rays(scene);
  const ReflectionFrame frame = frame_at(scene, kKeyEye);
  const ReflectionDepthImage key = make_reflection_depth_image(frame, trace_reflections(scene, rays, frame), 1e3f);
  const vec3 eye = kKeyEye + kMove;
  BestMatchStats st;
  const OffsetBuffer offsets = best_match_search(key, eye, nullptr, {}, &st);
  EXPECT_EQ(st.searched, frame.sample_count());
  size_t checked = 0, matched = 0, valid_expected = 0;
  float worst = 0.0f;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (key.object.at(x, y) == kNoReflector) continue;
      // The point of the mirror plane y = 0 that reflects R towards the new eye: where the
      // line from the eye to R mirrored in the plane crosses it.
      vec3 r = key_reflected_point(key, x, y);
      const vec3 r_mirrored(r.x, -r.y, r.z);
      const float t = eye.y / (eye.y - r_mirrored.y);
      const vec3 w_star = eye + t * (r_mirrored - eye);
      const auto p = project(key.camera, w_star);
      ASSERT_TRUE(p.has_value());
      // Only where the analytic match lies well inside the mirror's image (not within 2
      // pixels of its silhouette, where Algorithm 9 may rightly give INVALID).
      const int px = int(std::floor(p->pixel.x)), py = int(std::floor(p->pixel.y));
      bool interior = px >= 2 && py >= 2 && px < kSize - 2 && py < kSize - 2;
      for (int dy = -2; interior && dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx)
          if (key.object.at(px + dx, py + dy) == kNoReflector) interior = false;
      if (!interior) continue;
      ++valid_expected;
      const size_t i = size_t(y) * kSize + size_t(x);
      if (!offsets.valid[i]) continue;
      ++checked;
      const vec2 expected = p->pixel - vec2(float(x) + 0.5f, float(y) + 0.5f);
      const float err = std::max(std::abs(offsets.offset[i].x - expected.x), std::abs(offsets.offset[i].y - expected.y));
      worst = std::max(worst, err);
      matched += err <= 1.0f;
    }
  ASSERT_GT(valid_expected, 1000u);
  EXPECT_EQ(checked, valid_expected);  // no interior match is INVALID
  EXPECT_EQ(matched, checked) << "worst offset error " << worst << " px";
  // The camera moved: the offsets are not all zero (the test is not vacuous).
  float longest = 0.0f;
  for (size_t i = 0; i < offsets.offset.size(); ++i)
    if (offsets.valid[i]) longest = std::max(longest, glm::length(offsets.offset[i]));
  EXPECT_GT(longest, 3.0f);
}

TEST(TemporalReflections, DirectReprojectionIsWrongWhereTemporalReuseIsRight) {
  const Scene scene = floor_mirror(false);
  RayScene rays(scene);
  const ReflectionFrame frame0 = frame_at(scene, kKeyEye);
  const ReflectionDepthImage key = make_reflection_depth_image(frame0, trace_reflections(scene, rays, frame0), 1e3f);
  const ReflectionFrame frame1 = frame_at(scene, kKeyEye + kMove);
  const OffsetBuffer offsets = best_match_search(key, frame1.camera.position, nullptr, {});
  const IntermediateReflection mid = warp_reflections(key, offsets, {});
  const WarpedMesh mesh{&key, &offsets, &mid};
  const ReflectionReprojection temporal = reproject_reflections(frame1, key, mid.radiance, &mid.state, {}, &mesh);
  const ReflectionReprojection direct = reproject_reflections(frame1, key, key.radiance, nullptr, {});
  const TracedReflections truth = trace_reflections(scene, rays, frame1);
  // Compare on the samples both methods reuse (recomputed ones would be exact).
  std::vector<uint8_t> both(frame1.sample_count());
  size_t reused = 0;
  for (size_t i = 0; i < both.size(); ++i) reused += both[i] = temporal.flag[i] == kReuseOk && direct.flag[i] == kReuseOk;
  ASSERT_GT(reused, frame1.sample_count() / 2);
  const ImageU8 mask = mask_of(frame1, both);
  const ImageF reference = compose_reflections(frame1, truth.radiance);
  const double temporal_mae = compare_images(compose_reflections(frame1, temporal.radiance), reference, &mask).mae_avg;
  const double direct_mae = compare_images(compose_reflections(frame1, direct.radiance), reference, &mask).mae_avg;
  std::printf("planar mirror, %zu reused samples: temporal MAE %.3f, direct MAE %.3f, recomputed %llu of %zu\n", reused,
              temporal_mae, direct_mae, static_cast<unsigned long long>(temporal.recompute()), frame1.sample_count());
  // Stated bounds (0–255 display scale): temporal ≤ 1.0 (the goal), direct ≥ 3.0.
  EXPECT_LE(temporal_mae, 1.0);
  EXPECT_GE(direct_mae, 3.0);
  EXPECT_GT(direct_mae, 4.0 * temporal_mae);
  // Most of the mirror is reused, not recomputed.
  EXPECT_LT(double(temporal.recompute()), 0.25 * double(frame1.sample_count()));
}

TEST(TemporalReflections, DisoccludedPixelsAreFlaggedForRecomputation) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  const ReflectionFrame frame0 = frame_at(scene, kKeyEye);
  const ReflectionDepthImage key = make_reflection_depth_image(frame0, trace_reflections(scene, rays, frame0), 1e3f);
  // A sideways move so the box uncovers part of the mirror.
  const ReflectionFrame frame1 = frame_at(scene, kKeyEye + vec3(0.3f, 0.0f, 0.0f));
  const OffsetBuffer offsets = best_match_search(key, frame1.camera.position, nullptr, {});
  const IntermediateReflection mid = warp_reflections(key, offsets, {});
  const ReflectionReprojection r = reproject_reflections(frame1, key, mid.radiance, &mid.state, {});
  // Ground truth: the segment from the key eye to the sample's point is blocked.
  size_t hidden = 0, flagged = 0;
  const float eps = 1e-3f;
  for (size_t i = 0; i < frame1.sample_count(); ++i) {
    const vec3 d = frame1.position[i] - kKeyEye;
    if (!rays.occluded(Ray{kKeyEye, d, 0.0f, 1.0f - eps})) continue;
    ++hidden;
    flagged += (r.flag[i] & kReuseDisoccluded) != 0;
  }
  ASSERT_GT(hidden, 30u);
  // Pixel-centre sampling of the key view can disagree with the exact ray within a pixel
  // of the box's silhouette; everything else must be flagged.
  EXPECT_GE(double(flagged), 0.95 * double(hidden)) << flagged << " of " << hidden;
  EXPECT_GE(r.disoccluded, flagged);
}

// The buffers kept in the state and swapped with the caller's (temporal_reflections_into,
// key frames and reuse frames mixed, flags included) give the fresh path's bits.
TEST(TemporalReflections, ReusedBuffersGiveTheFreshResult) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  TemporalOptions options;
  options.keyframe_threshold = 0.05f;  // some key frames among the reuse frames
  TemporalState fresh_state, reused_state;
  std::vector<vec3> reused;
  std::vector<uint8_t> reused_flags;
  int keys = 0;
  for (int f = 0; f < 6; ++f) {
    const ReflectionFrame frame = frame_at(scene, kKeyEye + float(f) * kMove);
    TemporalFrameStats a, b;
    std::vector<uint8_t> fresh_flags;
    const std::vector<vec3> fresh = temporal_reflections(scene, rays, frame, fresh_state, options, &a, &fresh_flags);
    temporal_reflections_into(scene, rays, frame, reused_state, options, reused, &b, &reused_flags);
    keys += a.key;
    ASSERT_EQ(a.key, b.key) << f;
    ASSERT_EQ(a.recomputed, b.recomputed) << f;
    ASSERT_EQ(fresh, reused) << f;
    ASSERT_EQ(fresh_flags, reused_flags) << f;
  }
  EXPECT_GE(keys, 2);
  EXPECT_LT(keys, 6);
}

// trace_reflection_samples gives trace_reflections' radiance to the listed samples, and
// leaves the others as they were.
TEST(TemporalReflections, TracingListedSamplesMatchesTheFullTrace) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  const ReflectionFrame frame = frame_at(scene, kKeyEye);
  const TracedReflections full = trace_reflections(scene, rays, frame);
  std::vector<uint32_t> listed;
  for (uint32_t i = 0; i < frame.sample_count(); i += 3) listed.push_back(i);
  std::vector<vec3> radiance(frame.sample_count(), vec3(-1.0f));
  trace_reflection_samples(scene, rays, frame, listed, radiance);
  for (size_t i = 0; i < radiance.size(); ++i) ASSERT_EQ(radiance[i], i % 3 == 0 ? full.radiance[i] : vec3(-1.0f)) << i;
}

TEST(TemporalReflections, IdenticalForAnyThreadCount) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  auto run = [&](int threads) {
    ThreadLimit limit(threads);
    TemporalState state;
    std::vector<vec3> out;
    for (int f = 0; f < 3; ++f) {
      const std::vector<vec3> r = temporal_reflections(scene, rays, frame_at(scene, kKeyEye + float(f) * kMove), state, {});
      out.insert(out.end(), r.begin(), r.end());
    }
    return out;
  };
  const std::vector<vec3> one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (size_t i = 0; i < one.size(); ++i) ASSERT_EQ(one[i], two[i]) << i;
}

TEST(TemporalReflections, KeyFramePolicyFollowsTheThreshold) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  TemporalState state;
  TemporalOptions strict;
  strict.keyframe_threshold = 0.0f;  // any recomputed sample forces the next key frame
  TemporalFrameStats st;
  temporal_reflections(scene, rays, frame_at(scene, kKeyEye), state, strict, &st);
  EXPECT_TRUE(st.key);
  temporal_reflections(scene, rays, frame_at(scene, kKeyEye + vec3(0.3f, 0, 0)), state, strict, &st);
  EXPECT_FALSE(st.key);
  ASSERT_GT(st.recomputed, 0u);
  EXPECT_TRUE(state.need_key);
  temporal_reflections(scene, rays, frame_at(scene, kKeyEye + vec3(0.3f, 0, 0)), state, strict, &st);
  EXPECT_TRUE(st.key);
}

// The cost rule: a reuse frame whose work reaches the cycle's average work ends the cycle.
TEST(TemporalReflections, KeyFrameCostRuleEndsTheCycleWhenReuseStopsPaying) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  TemporalOptions options;
  options.keyframe_threshold = 1.0f;  // the threshold never fires: only the cost rule
  auto second_frame = [&](float cost, TemporalFrameStats& st) {
    options.keyframe_cost = cost;
    TemporalState state;
    temporal_reflections(scene, rays, frame_at(scene, kKeyEye), state, options, &st);
    EXPECT_TRUE(st.key);
    EXPECT_EQ(st.work, 1.0);
    temporal_reflections(scene, rays, frame_at(scene, kKeyEye + vec3(0.05f, 0, 0)), state, options, &st);
    EXPECT_FALSE(st.key);
    EXPECT_GT(st.rays, st.traced_rays);
    EXPECT_NEAR(st.work, (double(st.traced_rays) + double(cost) * double(state.key.pixels.size())) / double(st.rays),
                1e-12);
    return state.need_key;
  };
  TemporalFrameStats st;
  // Cheap fixed steps: the reuse frame's work is far below the cycle's average (1 + work) / 2.
  EXPECT_FALSE(second_frame(0.01f, st));
  EXPECT_LT(st.work, 0.5);
  // Fixed steps dearer than tracing every ray: reuse does not pay, the next frame is a key frame.
  EXPECT_TRUE(second_frame(2.0f, st));
  EXPECT_GT(st.work, 1.0);
  // Off: only the threshold decides.
  EXPECT_FALSE(second_frame(0.0f, st));
}

// A key frame built into the last one's buffers equals one built from scratch.
TEST(TemporalReflections, DepthImageIntoReusedBuffersEqualsAFreshOne) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  const ReflectionFrame a = frame_at(scene, kKeyEye), b = frame_at(scene, kKeyEye + vec3(0.4f, 0.2f, -0.3f));
  const float far = 100.0f * a.scene_diagonal;
  ReflectionDepthImage reused;
  make_reflection_depth_image_into(a, trace_reflections(scene, rays, a), far, reused);
  const TracedReflections tb = trace_reflections(scene, rays, b);
  make_reflection_depth_image_into(b, tb, far, reused);
  const ReflectionDepthImage fresh = make_reflection_depth_image(b, tb, far);
  ASSERT_NE(a.sample_count(), b.sample_count());  // the reset matters: another set of pixels
  EXPECT_EQ(reused.pixels, fresh.pixels);
  EXPECT_EQ(reused.reflected, fresh.reflected);
  auto same = [](const auto& x, const auto& y) { return std::ranges::equal(x.data(), y.data()); };
  EXPECT_TRUE(same(reused.object, fresh.object));
  EXPECT_TRUE(same(reused.position, fresh.position));
  EXPECT_TRUE(same(reused.normal, fresh.normal));
  EXPECT_TRUE(same(reused.depth, fresh.depth));
  EXPECT_TRUE(same(reused.specular, fresh.specular));
  EXPECT_TRUE(same(reused.radiance, fresh.radiance));
  EXPECT_TRUE(same(reused.distance, fresh.distance));
  EXPECT_TRUE(same(reused.spread, fresh.spread));
  EXPECT_TRUE(same(reused.lobe, fresh.lobe));
}

// A chrome ball (radius 0.25 m, 0.9 m above the floor mirror): its pixels minify the room,
// so a sub-pixel shift changes what they show; the warp must mark them unreliable (they
// are recomputed), while the planar floor mirror around it stays reliable.
TEST(TemporalReflections, CurvedMirrorPixelsAreUnreliablePlanarOnesAreNot) {
  Scene scene = floor_mirror(false);
  Mesh ball = make_sphere(0.25f, 48, 24);
  for (vec3& p : ball.positions) p += vec3(0.0f, 0.9f, 0.0f);
  const uint32_t ball_id = add_object(scene, ball, "ball", add_diffuse(scene, vec3(0.5f), 1.0f));
  const uint32_t floor_id = 0;
  ASSERT_EQ(scene.objects[floor_id].name, "mirror");
  RayScene rays(scene);
  const ReflectionFrame frame0 = frame_at(scene, kKeyEye);
  const ReflectionDepthImage key = make_reflection_depth_image(frame0, trace_reflections(scene, rays, frame0), 1e3f);
  // The measure itself: ≈ 1 on the plane (an isometry of directions), ≫ 1 on the ball
  // (about 1 + 2D/a ≈ 25 at D ≈ 3 m, a = 0.25 m).
  size_t plane = 0, plane_flat = 0, ball_px = 0, ball_curved = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const uint32_t o = key.object.at(x, y);
      if (o == floor_id) {
        ++plane;
        plane_flat += key.spread.at(x, y) < 1.01f;
      } else if (o == ball_id) {
        ++ball_px;
        ball_curved += key.spread.at(x, y) > 8.0f;
      }
    }
  ASSERT_GT(plane, 2000u);
  ASSERT_GT(ball_px, 50u);
  EXPECT_EQ(plane_flat, plane);
  EXPECT_GE(double(ball_curved), 0.9 * double(ball_px)) << ball_curved << " of " << ball_px;

  // A new camera: the ball's reused samples are flagged unreliable, the plane's mostly not.
  const ReflectionFrame frame1 = frame_at(scene, kKeyEye + kMove);
  const OffsetBuffer offsets = best_match_search(key, frame1.camera.position, nullptr, {});
  WarpOptions on;
  on.spread_limit = 8.0f;
  on.curved_contrast = -1.0f;  // every curved pixel, even where it shows a uniform background
  const IntermediateReflection mid = warp_reflections(key, offsets, on);
  EXPECT_GT(mid.curved, 0u);
  const WarpedMesh mesh{&key, &offsets, &mid};
  const ReflectionReprojection r = reproject_reflections(frame1, key, mid.radiance, &mid.state, {}, &mesh);
  size_t ball1 = 0, ball_ok = 0, plane1 = 0, plane_unreliable = 0;
  for (size_t i = 0; i < frame1.sample_count(); ++i) {
    if (frame1.reflector[i] == ball_id) {
      ++ball1;
      ball_ok += r.flag[i] == kReuseOk;
    } else if (frame1.reflector[i] == floor_id) {
      ++plane1;
      plane_unreliable += (r.flag[i] & kReuseUnreliable) != 0;
      EXPECT_EQ(r.flag[i] & kReuseCurved, 0) << i;
    }
  }
  ASSERT_GT(ball1, 50u);
  EXPECT_EQ(ball_ok, 0u);
  EXPECT_GT(r.curved, ball1 / 2);  // the rest: disoccluded, or an empty warp there
  EXPECT_LT(double(plane_unreliable), 0.1 * double(plane1)) << plane_unreliable << " of " << plane1;

  // With the rule off (the default) the same ball pixels would be reused.
  const WarpOptions off;
  const IntermediateReflection mid_off = warp_reflections(key, offsets, off);
  EXPECT_EQ(mid_off.curved, 0u);
  const WarpedMesh mesh_off{&key, &offsets, &mid_off};
  const ReflectionReprojection r_off = reproject_reflections(frame1, key, mid_off.radiance, &mid_off.state, {}, &mesh_off);
  size_t ball_ok_off = 0;
  for (size_t i = 0; i < frame1.sample_count(); ++i) ball_ok_off += frame1.reflector[i] == ball_id && r_off.flag[i] == kReuseOk;
  EXPECT_GT(ball_ok_off, ball1 / 4);
}

// The floor mirror reflecting a wall of vertical stripes (alternately 0.27 and 0.33 m wide,
// albedo 0.02 and 0.9: about 6 pixels each in the mirror): the reflected image is all sharp
// edges. A reused sample "crosses an edge" when its Lr lies between the two sides' levels,
// a blend no point sample of the scene has.
namespace {
Scene striped_mirror() {
  Scene scene;
  scene.name = "striped-mirror";
  add_quad(scene, vec3(-2, 0, -2), vec3(0, 0, 4), vec3(4, 0, 0), add_diffuse(scene, vec3(0.5f), 1.0f), "mirror");
  scene.ambient = vec3(1.0f);  // flat ambient shading, no lights: each stripe one level
  const uint32_t dark = add_diffuse(scene, vec3(0.02f)), bright = add_diffuse(scene, vec3(0.9f));
  float x = -4.0f;
  for (int k = 0; x < 4.0f; ++k) {
    const float width = k % 2 ? 0.33f : 0.27f;
    add_quad(scene, vec3(x, -1, -2), vec3(width, 0, 0), vec3(0, 6, 0), k % 2 ? bright : dark, "stripe");
    x += width;
  }
  return scene;
}

// Its key frame at kKeyEye and one camera step kMove: offsets, the traced truth.
struct StripedStep {
  Scene scene = striped_mirror();
  RayScene rays{scene};
  ReflectionFrame frame0 = frame_at(scene, kKeyEye);
  ReflectionDepthImage key = make_reflection_depth_image(frame0, trace_reflections(scene, rays, frame0), 1e3f);
  ReflectionFrame frame1 = frame_at(scene, kKeyEye + kMove);
  OffsetBuffer offsets = best_match_search(key, frame1.camera.position, nullptr, {});
  TracedReflections truth = trace_reflections(scene, rays, frame1);
  ImageF reference = compose_reflections(frame1, truth.radiance);
};
}  // namespace

TEST(TemporalReflections, EdgeRuleNeverReusesAcrossAReflectedEdge) {
  const StripedStep step;
  const auto& [scene, rays, frame0, key, frame1, offsets, truth, reference] = step;

  // The two sides' levels from the traced frame: the dark stripes' brightest Lr and the
  // bright ones' darkest (albedo ratio 45; the light varies far less across the wall).
  auto luminance = [](vec3 c) { return (c.x + c.y + c.z) / 3.0f; };
  std::vector<float> levels;
  for (const vec3& c : truth.radiance) levels.push_back(luminance(c));
  std::sort(levels.begin(), levels.end());
  const float median = levels[levels.size() / 2];
  float dark_max = 0.0f, bright_min = kInf;
  for (float l : levels) {
    if (l < 0.2f * median) dark_max = std::max(dark_max, l);
    else bright_min = std::min(bright_min, l);
  }
  ASSERT_GT(bright_min, 4.0f * dark_max);  // two well-separated levels
  auto across = [&](vec3 c) { const float l = luminance(c); return l > 1.5f * dark_max && l < bright_min / 1.5f; };
  size_t traced_across = 0;
  for (const vec3& c : truth.radiance) traced_across += across(c);
  EXPECT_EQ(traced_across, 0u);  // no point sample lies between the sides

  struct Outcome {
    size_t reused = 0, across = 0;
    double mae = 0.0, reused_mae = 0.0;
    uint64_t recomputed = 0, edge = 0;
  };
  auto run = [&](const WarpOptions& warp) {
    const IntermediateReflection mid = warp_reflections(key, offsets, warp);
    const WarpedMesh mesh{&key, &offsets, &mid, warp.edge_contrast, warp.edge_rule};
    ReflectionReprojection r = reproject_reflections(frame1, key, mid.radiance, &mid.state, {}, &mesh);
    Outcome o;
    std::vector<uint8_t> ok(frame1.sample_count());
    for (size_t i = 0; i < ok.size(); ++i) {
      ok[i] = r.flag[i] == kReuseOk;
      o.reused += ok[i];
      o.across += ok[i] && across(r.radiance[i]);
      if (!ok[i]) r.radiance[i] = truth.radiance[i];  // recomputed: what the ray tracer gives
    }
    const ImageF color = compose_reflections(frame1, r.radiance);
    const ImageU8 all_mask = mask_of(frame1, std::vector<uint8_t>(ok.size(), 1));
    o.mae = compare_images(color, reference, &all_mask).mae_avg;
    const ImageU8 reused_mask = mask_of(frame1, ok);
    o.reused_mae = compare_images(color, reference, &reused_mask).mae_avg;
    o.recomputed = r.recompute();
    o.edge = r.edge;
    return o;
  };
  WarpOptions off, nearest, recompute;
  nearest.edge_contrast = recompute.edge_contrast = 0.05f;
  recompute.edge_rule = ReflectedEdgeRule::kRecompute;
  const Outcome o_off = run(off), o_near = run(nearest), o_rec = run(recompute);
  std::printf("striped wall in a planar mirror, %zu samples: MAE off %.3f (%zu reused, %zu across an edge), "
              "nearest %.3f (%zu, %zu), recompute %.3f (%zu, %zu; %llu recomputed, %llu on edges)\n",
              frame1.sample_count(), o_off.mae, o_off.reused, o_off.across, o_near.mae, o_near.reused, o_near.across,
              o_rec.mae, o_rec.reused, o_rec.across, static_cast<unsigned long long>(o_rec.recomputed),
              static_cast<unsigned long long>(o_rec.edge));
  ASSERT_GT(o_off.reused, frame1.sample_count() / 2);
  // Blending the key frame's point samples puts many reused samples between the sides ...
  EXPECT_GT(o_off.across, o_off.reused / 20);
  // ... the rule none, whether it takes the nearest corner or recomputes the edge.
  EXPECT_EQ(o_near.across, 0u);
  EXPECT_EQ(o_rec.across, 0u);
  EXPECT_EQ(o_near.reused, o_off.reused);  // nearest: the same samples reused
  EXPECT_EQ(o_off.edge, 0u);
  EXPECT_GT(o_rec.edge, 0u);
  // Lower error than blending: nearest on the same samples, recompute at least halves it.
  EXPECT_LT(o_near.mae, o_off.mae);
  EXPECT_LT(o_rec.mae, 0.5 * o_off.mae);

  // Same bits for 1 and 2 threads with the rule on (and splats recomputed; blend_error), through the
  // whole method.
  WarpOptions splats = recompute;
  splats.recompute_splats = true;
  WarpOptions risk;
  risk.blend_error = 8.0f;
  for (const WarpOptions& warp : {nearest, recompute, splats, risk}) {
    auto frames = [&](int threads) {
      ThreadLimit limit(threads);
      TemporalOptions options;
      options.warp = warp;
      TemporalState state;
      std::vector<vec3> out;
      for (int f = 0; f < 3; ++f) {
        const std::vector<vec3> r =
            temporal_reflections(scene, rays, frame_at(scene, kKeyEye + float(f) * kMove), state, options);
        out.insert(out.end(), r.begin(), r.end());
      }
      return out;
    };
    EXPECT_EQ(frames(1), frames(2));
  }
}

TEST(TemporalReflections, BlendRiskIsTheExpectedErrorOfTheBlend) {
  auto display = [](float linear) { return 255.0f * linear_to_srgb(linear); };
  BlendSamples edge;
  edge.n = 3;
  edge.lr[0] = edge.lr[1] = vec3(0.0f), edge.lr[2] = vec3(1.0f, 0.5f, 0.0f);
  auto weights = [&](float a, float b, float c) { edge.w[0] = a, edge.w[1] = b, edge.w[2] = c; };
  weights(1.0f, 0.0f, 0.0f);  // on a sample: no doubt
  EXPECT_FLOAT_EQ(blend_risk(edge, edge.lr[0], 1.0f, vec3(0.0f)), 0.0f);
  // Halfway between black and white: either side with probability ½, D(½) and 255 − D(½) away.
  weights(0.5f, 0.0f, 0.5f);
  EXPECT_NEAR(blend_risk(edge, vec3(0.5f, 0.25f, 0.0f), 1.0f, vec3(0.0f)), 127.5f, 1e-3f);
  // Weights are normalised: 2/3 of the time at 0, 1/3 at 1, value 1/3.
  weights(1.0f, 1.0f, 1.0f);
  EXPECT_NEAR(blend_risk(edge, vec3(1.0f / 3.0f, 1.0f / 6.0f, 0.0f), 1.0f, vec3(0.0f)),
              2.0f / 3.0f * display(1.0f / 3.0f) + 1.0f / 3.0f * (255.0f - display(1.0f / 3.0f)), 1e-3f);
  // s scales the reflection: a faint one risks less (and the display is non-linear).
  weights(0.5f, 0.0f, 0.5f);
  EXPECT_NEAR(blend_risk(edge, vec3(0.5f, 0.25f, 0.0f), 0.1f, vec3(0.0f)), 0.5f * display(0.1f), 1e-3f);
  // Where the diffuse part already saturates the display, no reuse can be seen to be wrong.
  EXPECT_FLOAT_EQ(blend_risk(edge, vec3(0.5f, 0.25f, 0.0f), 1.0f, vec3(1.0f)), 0.0f);
  BlendSamples flat;
  flat.n = 2;
  flat.lr[0] = flat.lr[1] = vec3(0.3f), flat.w[0] = flat.w[1] = 1.0f;
  EXPECT_FLOAT_EQ(blend_risk(flat, vec3(0.3f), 1.0f, vec3(0.1f)), 0.0f);
}

// blend_error ranks reused samples by the error their blend is likely to carry: on the
// striped mirror a higher threshold recomputes fewer samples and removes more error per
// recomputed sample (the first recomputes pay the most), and a low one nearly all of it.
TEST(TemporalReflections, BlendErrorSpendsRecomputesWhereTheErrorIs) {
  const StripedStep step;
  const auto& [scene, rays, frame0, key, frame1, offsets, truth, reference] = step;
  struct Outcome {
    double mae = 0.0;
    uint64_t recomputed = 0, edge = 0;
  };
  auto run = [&](const WarpOptions& warp) {
    const IntermediateReflection mid = warp_reflections(key, offsets, warp);
    const WarpedMesh mesh{&key, &offsets, &mid, warp.edge_contrast, warp.edge_rule, warp.recompute_splats,
                          warp.blend_error};
    ReflectionReprojection r = reproject_reflections(frame1, key, mid.radiance, &mid.state, {}, &mesh);
    for (size_t i = 0; i < r.flag.size(); ++i)
      if (r.flag[i] != kReuseOk) r.radiance[i] = truth.radiance[i];
    const ImageU8 all = mask_of(frame1, std::vector<uint8_t>(frame1.sample_count(), 1));
    return Outcome{compare_images(compose_reflections(frame1, r.radiance), reference, &all).mae_avg, r.recompute(),
                   r.edge};
  };
  WarpOptions edges, low, high;
  edges.edge_contrast = 0.05f;
  edges.edge_rule = ReflectedEdgeRule::kRecompute;
  low.blend_error = 4.0f;  // display levels
  high.blend_error = 40.0f;
  const Outcome off = run({}), o_edges = run(edges), o_low = run(low), o_high = run(high);
  auto removed_per_sample = [&](const Outcome& o) {
    return (off.mae - o.mae) / double(std::max<uint64_t>(o.recomputed - off.recomputed, 1));
  };
  std::printf("striped mirror: MAE off %.3f (%llu recomputed); edge 0.05 %.3f (+%llu, %.5f per sample); "
              "blend error 4 %.3f (+%llu, %.5f), 40 %.3f (+%llu, %.5f)\n",
              off.mae, static_cast<unsigned long long>(off.recomputed), o_edges.mae,
              static_cast<unsigned long long>(o_edges.recomputed - off.recomputed), removed_per_sample(o_edges),
              o_low.mae, static_cast<unsigned long long>(o_low.recomputed - off.recomputed), removed_per_sample(o_low),
              o_high.mae, static_cast<unsigned long long>(o_high.recomputed - off.recomputed),
              removed_per_sample(o_high));
  EXPECT_EQ(off.edge, 0u);  // off by default
  ASSERT_GT(o_high.edge, 0u);
  EXPECT_EQ(o_low.recomputed, off.recomputed + o_low.edge);  // only its own flags added
  EXPECT_LT(o_high.recomputed, o_low.recomputed);
  EXPECT_GT(removed_per_sample(o_high), removed_per_sample(o_low));
  EXPECT_LT(o_high.mae, 0.5 * off.mae);
  EXPECT_LT(o_low.mae, 0.1 * off.mae);
}

// Feedback from observed error: the blend-error rule's samples keep their reuse value, so
// the recompute sees its error; above refine_error their reused neighbours are traced too,
// above learn_error their key pixels are marked and later frames of the key cycle trace the
// samples reusing them. Every traced sample is counted, and each is the full trace's value.
TEST(TemporalReflections, FeedbackTracesWhereReuseWasSeenToErr) {
  const Scene scene = striped_mirror();
  RayScene rays(scene);
  struct Run {
    std::vector<TemporalFrameStats> stats;
    double mae = 0.0;
    std::vector<vec3> radiance;
  };
  auto run = [&](float refine, float learn, int threads) {
    ThreadLimit limit(threads);
    TemporalOptions o;
    o.warp.blend_error = 8.0f;
    o.keyframe_threshold = 1.0f;  // one key cycle
    o.refine_error = refine;
    o.learn_error = learn;
    TemporalState state;
    Run out;
    for (int f = 0; f < 4; ++f) {
      const ReflectionFrame frame = frame_at(scene, kKeyEye + 0.5f * float(f) * kMove);
      TemporalFrameStats st;
      std::vector<uint8_t> flags;
      const std::vector<vec3> r = temporal_reflections(scene, rays, frame, state, o, &st, &flags);
      const TracedReflections truth = trace_reflections(scene, rays, frame);
      uint64_t flagged = 0, refined = 0, learned = 0, traced_rays = 0;
      const int w = frame.camera.width;
      std::vector<int> sample_at(size_t(w) * size_t(frame.camera.height), -1);
      for (size_t i = 0; i < flags.size(); ++i) sample_at[frame.pixel[i]] = int(i);
      for (size_t i = 0; i < flags.size(); ++i) {
        if (flags[i] == kReuseOk) continue;
        ++flagged, refined += (flags[i] & kReuseRefined) != 0, learned += (flags[i] & kReuseLearned) != 0;
        traced_rays += frame.first_ray[i + 1] - frame.first_ray[i];
        EXPECT_EQ(r[i], truth.radiance[i]) << "frame " << f << " sample " << i;
        if (!(flags[i] & kReuseRefined)) continue;
        // A refined sample is next to an observed one (its reuse value kept) on its reflector.
        bool beside_observed = false;
        const int x = int(frame.pixel[i]) % w, y = int(frame.pixel[i]) / w;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= frame.camera.height) continue;
            const int j = sample_at[size_t(ny) * size_t(w) + size_t(nx)];
            beside_observed = beside_observed || (j >= 0 && (flags[size_t(j)] & kReuseKept) &&
                                                  frame.reflector[size_t(j)] == frame.reflector[i]);
          }
        EXPECT_TRUE(beside_observed) << "frame " << f << " sample " << i;
      }
      if (!st.key) {
        EXPECT_EQ(st.recomputed, flagged) << f;
        EXPECT_EQ(st.refined, refined) << f;
        EXPECT_EQ(st.learned, learned) << f;
        EXPECT_EQ(st.traced_rays, traced_rays) << f;
        if (f == 1) {
          EXPECT_EQ(st.learned, 0u);  // no earlier frame of the cycle marked anything
        }
        const ImageU8 all = mask_of(frame, std::vector<uint8_t>(frame.sample_count(), 1));
        out.mae += compare_images(compose_reflections(frame, r), compose_reflections(frame, truth.radiance), &all)
                       .mae_avg;
      }
      out.stats.push_back(st);
      out.radiance.insert(out.radiance.end(), r.begin(), r.end());
    }
    return out;
  };
  auto total = [](const Run& r, uint64_t TemporalFrameStats::*field) {
    uint64_t n = 0;
    for (const TemporalFrameStats& st : r.stats) n += st.*field;
    return n;
  };
  const Run off = run(kInf, kInf, 1), refine = run(16.0f, kInf, 1), learn = run(kInf, 16.0f, 1),
            both = run(16.0f, 16.0f, 1), both2 = run(16.0f, 16.0f, 2);
  std::printf("striped mirror, 3 reuse frames: MAE sum off %.3f (%llu recomputed), refine %.3f (+%llu refined), "
              "learn %.3f (+%llu learned)\n",
              off.mae, static_cast<unsigned long long>(total(off, &TemporalFrameStats::recomputed)), refine.mae,
              static_cast<unsigned long long>(total(refine, &TemporalFrameStats::refined)), learn.mae,
              static_cast<unsigned long long>(total(learn, &TemporalFrameStats::learned)));
  EXPECT_EQ(total(off, &TemporalFrameStats::refined) + total(off, &TemporalFrameStats::learned), 0u);
  EXPECT_EQ(total(off, &TemporalFrameStats::observed), 0u);
  ASSERT_GT(total(refine, &TemporalFrameStats::refined), 0u);
  ASSERT_GT(total(learn, &TemporalFrameStats::learned), 0u);
  EXPECT_EQ(total(learn, &TemporalFrameStats::refined), 0u);
  EXPECT_EQ(total(refine, &TemporalFrameStats::learned), 0u);
  // The same key frames and the same rule flags: only the feedback's samples were added, and
  // each is now exact, so the error can only fall.
  EXPECT_EQ(total(refine, &TemporalFrameStats::recomputed),
            total(off, &TemporalFrameStats::recomputed) + total(refine, &TemporalFrameStats::refined));
  EXPECT_EQ(total(learn, &TemporalFrameStats::recomputed),
            total(off, &TemporalFrameStats::recomputed) + total(learn, &TemporalFrameStats::learned));
  EXPECT_LT(refine.mae, off.mae);
  EXPECT_LT(learn.mae, off.mae);
  // Any thread count: the same samples traced, the same values.
  ASSERT_EQ(both.radiance.size(), both2.radiance.size());
  for (size_t i = 0; i < both.radiance.size(); ++i) ASSERT_EQ(both.radiance[i], both2.radiance[i]) << i;
  for (size_t f = 0; f < both.stats.size(); ++f) {
    EXPECT_EQ(both.stats[f].recomputed, both2.stats[f].recomputed) << f;
    EXPECT_EQ(both.stats[f].learned, both2.stats[f].learned) << f;
  }
}

// Key samples no warp triangle reached are splatted as lone points; with recompute_splats
// they are unreliable (recomputed) instead of reused through the bilinear fallback.
TEST(TemporalReflections, RecomputeSplatsMarksSplattedPointsUnreliable) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  const ReflectionFrame frame0 = frame_at(scene, kKeyEye);
  const ReflectionDepthImage key = make_reflection_depth_image(frame0, trace_reflections(scene, rays, frame0), 1e3f);
  const OffsetBuffer offsets = best_match_search(key, kKeyEye + vec3(0.3f, 0.0f, 0.0f), nullptr, {});
  auto splats = [&](const IntermediateReflection& mid, uint8_t state) {
    size_t n = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        n += mid.state.at(x, y) == state && mid.triangle.at(x, y) == kNoWarpTriangle;
    return n;
  };
  const IntermediateReflection off = warp_reflections(key, offsets, {});
  WarpOptions on;
  on.recompute_splats = true;
  const IntermediateReflection mid = warp_reflections(key, offsets, on);
  const size_t reused_splats = splats(off, kWarpReliable);
  ASSERT_GT(reused_splats, 0u);  // the case has splats (next to the box's dropped triangles)
  EXPECT_EQ(splats(mid, kWarpReliable), 0u);
  EXPECT_EQ(splats(mid, kWarpUnreliable), reused_splats);
  // Everything the triangles drew is unchanged.
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      if (off.triangle.at(x, y) != kNoWarpTriangle) {
        ASSERT_EQ(mid.state.at(x, y), off.state.at(x, y));
      }
}

// The table blend_risk_exceeds reads stays within its stated bound of linear_to_srgb, on a
// fine sweep of [0, 1] and around the linear segment's end.
TEST(TemporalReflections, SrgbTableIsWithinItsBound) {
  const float bound = linear_to_srgb_approx_error();
  float worst = 0.0f;
  constexpr int kSteps = 1 << 18;
  for (int j = 0; j <= kSteps; ++j) {
    const float l = float(j) / float(kSteps);
    worst = std::max(worst, std::abs(linear_to_srgb_approx(l) - linear_to_srgb(l)));
  }
  for (float l = 0.0030f; l < 0.0033f; l = std::nextafter(l, 1.0f))
    worst = std::max(worst, std::abs(linear_to_srgb_approx(l) - linear_to_srgb(l)));
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.0f);  // an approximation (the test would not notice a wrong bound otherwise)
}

// blend_risk_exceeds is blend_risk(...) > limit for every input: random blends, limits far
// from and just around the exact risk, NaN, zero and infinite weights.
TEST(TemporalReflections, BlendRiskExceedsIsTheExactDecision) {
  uint32_t seed = 12345u;
  auto uniform = [&] {  // fixed LCG: the same cases everywhere
    seed = seed * 1664525u + 1013904223u;
    return float(seed >> 8) / float(1u << 24);
  };
  int exceeded = 0, cases = 0;
  for (int t = 0; t < 20000; ++t) {
    BlendSamples blend;
    blend.n = 1 + int(uniform() * 4.0f) % 4;
    for (int k = 0; k < blend.n; ++k) {
      blend.lr[k] = vec3(2.0f * uniform(), 2.0f * uniform(), 2.0f * uniform());
      blend.w[k] = uniform() < 0.1f ? 0.0f : uniform();
    }
    const vec3 value = uniform() < 0.5f ? blend.lr[0] : vec3(uniform(), uniform(), uniform());
    const float s = uniform() < 0.2f ? 1.0f : uniform();
    const vec3 base = uniform() < 0.3f ? vec3(0.0f) : vec3(uniform(), uniform(), uniform()) * 0.5f;
    const float risk = blend_risk(blend, value, s, base);
    const float limits[] = {8.0f, 40.0f * uniform(), risk, std::nextafter(risk, 0.0f), std::nextafter(risk, kInf),
                            risk + 0.01f, risk - 0.01f, 0.0f, kInf};
    for (const float limit : limits) {
      ASSERT_EQ(blend_risk_exceeds(blend, value, s, base, limit), risk > limit)
          << "case " << t << " limit " << limit << " risk " << risk;
      exceeded += risk > limit;
      ++cases;
    }
  }
  EXPECT_GT(exceeded, cases / 10);  // both answers are exercised
  EXPECT_LT(exceeded, cases * 9 / 10);
  BlendSamples odd;
  odd.n = 2;
  odd.lr[0] = vec3(0.2f), odd.lr[1] = vec3(0.8f, 0.1f, 0.3f);
  odd.w[0] = 1.0f, odd.w[1] = 1.0f;
  const float nan = std::nanf("");
  for (const vec3 value : {vec3(nan, 0.5f, 0.5f), vec3(0.5f)})
    for (const float w1 : {0.0f, 1.0f, kInf, nan})
      for (const float limit : {0.0f, 8.0f, 100.0f}) {
        odd.w[1] = w1;
        EXPECT_EQ(blend_risk_exceeds(odd, value, 1.0f, vec3(0.0f), limit),
                  blend_risk(odd, value, 1.0f, vec3(0.0f)) > limit);
      }
  BlendSamples none;
  EXPECT_FALSE(blend_risk_exceeds(none, vec3(0.5f), 1.0f, vec3(0.0f), 0.0f));
}

// blend_risk_exceeds settles most blends of similar samples by the display curve's slope
// (12.92 at most) before its table: that must never change a decision. Blends of samples a
// little apart, so the risk falls on both sides of the limit and near it.
TEST(TemporalReflections, BlendRiskExceedsIsTheExactDecisionForSimilarSamples) {
  // The slope bound it rests on, on a fine sweep: the curve and the table's chords.
  constexpr int kSteps = 1 << 16;
  for (int j = 0; j < kSteps; ++j) {
    const float a = float(j) / float(kSteps), b = float(j + 1) / float(kSteps);
    ASSERT_LE(std::abs(linear_to_srgb(b) - linear_to_srgb(a)), 12.92f * (b - a) + 4e-7f) << a;
    ASSERT_LE(std::abs(linear_to_srgb_approx(b) - linear_to_srgb_approx(a)), 12.9213f * (b - a) + 6e-7f) << a;
  }
  uint32_t seed = 987u;
  auto uniform = [&] {
    seed = seed * 1664525u + 1013904223u;
    return float(seed >> 8) / float(1u << 24);
  };
  int exceeded = 0, cases = 0;
  for (int t = 0; t < 40000; ++t) {
    BlendSamples blend;
    blend.n = 1 + t % 4;
    const vec3 centre(uniform(), uniform(), uniform());
    const float spread = 0.01f * uniform() * uniform();
    for (int k = 0; k < blend.n; ++k) {
      blend.lr[k] = centre + spread * (vec3(uniform(), uniform(), uniform()) - 0.5f);
      blend.w[k] = uniform();
    }
    const vec3 value = t % 3 == 0 ? blend.lr[0] : centre;
    const float s = t % 5 == 0 ? 1.0f : uniform();
    const vec3 base = t % 7 == 0 ? vec3(0.0f) : 0.3f * vec3(uniform(), uniform(), uniform());
    const float risk = blend_risk(blend, value, s, base);
    for (const float limit : {8.0f, 0.5f, 2.0f * uniform(), risk, risk + 0.2f, risk - 0.2f, risk * 1.1f,
                              risk * 0.9f, risk / 0.95f, risk * 0.95f}) {
      ASSERT_EQ(blend_risk_exceeds(blend, value, s, base, limit), risk > limit)
          << "case " << t << " limit " << limit << " risk " << risk;
      exceeded += risk > limit;
      ++cases;
    }
  }
  EXPECT_GT(exceeded, cases / 10);
  EXPECT_LT(exceeded, cases * 9 / 10);
}

namespace {
// The same images and counters, bit for bit.
void expect_same_warp(const IntermediateReflection& reused, const IntermediateReflection& fresh) {
  EXPECT_TRUE(reused.radiance == fresh.radiance);
  EXPECT_TRUE(reused.depth == fresh.depth);
  EXPECT_TRUE(reused.state == fresh.state);
  EXPECT_TRUE(reused.triangle == fresh.triangle);
  EXPECT_EQ(reused.triangles, fresh.triangles);
  EXPECT_EQ(reused.discontinuous, fresh.discontinuous);
  EXPECT_EQ(reused.stretched, fresh.stretched);
  EXPECT_EQ(reused.curved, fresh.curved);
  EXPECT_EQ(reused.edges, fresh.edges);
}
}  // namespace

// warp_reflections_into over a buffer last written from another key frame (same size, other
// reflective pixels) gives exactly what a fresh warp gives.
TEST(TemporalReflections, WarpIntoAReusedBufferIsAFreshWarp) {
  const Scene first = floor_mirror(true), second = floor_mirror(false);
  RayScene rays_first(first), rays_second(second);
  const ReflectionFrame frame_a = frame_at(first, kKeyEye);
  const ReflectionFrame frame_b = frame_at(second, kKeyEye + vec3(0.3f, 0.2f, 0.1f));
  const ReflectionDepthImage key_a =
      make_reflection_depth_image(frame_a, trace_reflections(first, rays_first, frame_a), 1e3f);
  const ReflectionDepthImage key_b =
      make_reflection_depth_image(frame_b, trace_reflections(second, rays_second, frame_b), 1e3f);
  ASSERT_NE(key_a.pixels, key_b.pixels);
  const OffsetBuffer offsets_a = best_match_search(key_a, kKeyEye + kMove, nullptr, {});
  const OffsetBuffer offsets_b = best_match_search(key_b, kKeyEye + vec3(0.3f, 0.2f, 0.1f) + kMove, nullptr, {});
  IntermediateReflection reused;
  warp_reflections_into(key_a, offsets_a, {}, reused);
  warp_reflections_into(key_b, offsets_b, {}, reused);
  expect_same_warp(reused, warp_reflections(key_b, offsets_b, {}));
}

// The warp keeps per-key-frame tables (candidate triangles, compact vertices): a key frame
// rebuilt in place (same object) or new options must rebuild them, so the reused warp
// equals a fresh one, also as read by warped_radiance_at.
TEST(TemporalReflections, WarpAfterAKeyRebuiltInPlaceIsAFreshWarp) {
  const Scene first = floor_mirror(true), second = floor_mirror(false);
  RayScene rays_first(first), rays_second(second);
  const vec3 eye_b = kKeyEye + vec3(0.3f, 0.2f, 0.1f);
  const ReflectionFrame frame_a = frame_at(first, kKeyEye), frame_b = frame_at(second, eye_b);
  ReflectionDepthImage key;
  make_reflection_depth_image_into(frame_a, trace_reflections(first, rays_first, frame_a), 1e3f, key);
  const std::vector<uint32_t> pixels_a = key.pixels;
  const OffsetBuffer offsets_a = best_match_search(key, kKeyEye + kMove, nullptr, {});
  IntermediateReflection reused;
  warp_reflections_into(key, offsets_a, {}, reused);
  make_reflection_depth_image_into(frame_b, trace_reflections(second, rays_second, frame_b), 1e3f, key);
  ASSERT_NE(pixels_a, key.pixels);
  const OffsetBuffer offsets_b = best_match_search(key, eye_b + kMove, nullptr, {});
  WarpOptions strict;  // every per-key flag on: curved, edge, discontinuity
  strict.spread_limit = 1.5f;
  strict.curved_contrast = -1.0f;
  strict.edge_contrast = 0.05f;
  strict.edge_rule = ReflectedEdgeRule::kRecompute;
  strict.depth_discontinuity = 0.02f;
  for (const WarpOptions& options : {WarpOptions{}, strict, WarpOptions{}}) {
    warp_reflections_into(key, offsets_b, options, reused);
    const IntermediateReflection fresh = warp_reflections(key, offsets_b, options);
    expect_same_warp(reused, fresh);
    const WarpedMesh mesh_reused{&key, &offsets_b, &reused}, mesh_fresh{&key, &offsets_b, &fresh};
    int hits = 0;
    for (int y = 0; y < key.object.height(); y += 3)
      for (int x = 0; x < key.object.width(); x += 3) {
        const vec2 q(float(x) + 0.37f, float(y) + 0.61f);
        vec3 a(0.0f), b(0.0f);
        const bool hit = warped_radiance_at(mesh_reused, q, a);
        ASSERT_EQ(hit, warped_radiance_at(mesh_fresh, q, b));
        if (hit) {
          EXPECT_TRUE(a == b);
          ++hits;
        }
      }
    EXPECT_GT(hits, 0);
  }
}

// warped_radiance_at (four triangles at a time) is the rule it states, as a plain loop: the
// triangles stored at the reliable pixels of the 3×3 around q, row by row, the first whose
// edge functions (signed by the orientation) are all ≥ 0, or ≥ −kEdgeSlack·√|area2| (1e-3),
// wins; its barycentrics are those edge functions clamped at 0. Bit for bit, at points
// around every pixel of a warp: near vertices, on edges, outside.
TEST(TemporalReflections, WarpedRadianceAtIsTheFirstTriangleThatContainsQ) {
  const Scene scene = floor_mirror(true);
  RayScene rays(scene);
  const ReflectionFrame frame = frame_at(scene, kKeyEye);
  const ReflectionDepthImage key =
      make_reflection_depth_image(frame, trace_reflections(scene, rays, frame), 1e3f);
  const OffsetBuffer offsets = best_match_search(key, kKeyEye + kMove, nullptr, {});
  const IntermediateReflection mid = warp_reflections(key, offsets, {});
  const WarpedMesh mesh{&key, &offsets, &mid};
  const int w = key.object.width(), h = key.object.height();
  auto cross = [](vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; };
  int hits = 0, misses = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (const vec2 d :
           {vec2(0.5f), vec2(0.0f), vec2(0.37f, 0.61f), vec2(0.999f, 0.25f), vec2(0.5f, 0.0001f)}) {
        const vec2 q = vec2(float(x), float(y)) + d;
        bool want = false;
        uint32_t want_corner[3] = {};
        float want_b[3] = {};
        for (int yy = y - 1; yy <= y + 1 && !want; ++yy)
          for (int xx = x - 1; xx <= x + 1 && !want; ++xx) {
            if (xx < 0 || yy < 0 || xx >= w || yy >= h || mid.state.at(xx, yy) != kWarpReliable) continue;
            const uint32_t id = mid.triangle.at(xx, yy);
            if (id == kNoWarpTriangle) continue;
            const uint32_t quad = id / 2u, half = id % 2u, qx = quad % uint32_t(w), qy = quad / uint32_t(w);
            const uint32_t c[3] = {mid.index[quad], mid.index[(qy + half) * uint32_t(w) + qx + 1u],
                                   mid.index[(qy + 1u) * uint32_t(w) + qx + 1u - half]};
            const vec2 p[3] = {mid.point[c[0]], mid.point[c[1]], mid.point[c[2]]};
            const float area2 = cross(p[1] - p[0], p[2] - p[0]);
            if (std::abs(area2) < 1e-12f) continue;
            float e[3];
            for (int k = 0; k < 3; ++k) {
              const vec2 a = p[(k + 1) % 3], b = p[(k + 2) % 3];
              e[k] = area2 < 0.0f ? -cross(b - a, q - a) : cross(b - a, q - a);
            }
            const bool inside = e[0] >= 0.0f && e[1] >= 0.0f && e[2] >= 0.0f;
            const float slack = inside ? 0.0f : 1e-3f * std::sqrt(std::abs(area2));
            if (e[0] < -slack || e[1] < -slack || e[2] < -slack) continue;
            want = true;
            for (int k = 0; k < 3; ++k) want_corner[k] = c[k], want_b[k] = std::max(e[k], 0.0f);
          }
        vec3 radiance(-1.0f);
        BlendSamples blend;
        ASSERT_EQ(warped_radiance_at(mesh, q, radiance, &blend), want) << q.x << " " << q.y;
        if (!want) {
          ++misses;
          continue;
        }
        ++hits;
        ASSERT_EQ(blend.n, 3);
        for (int k = 0; k < 3; ++k) {
          ASSERT_EQ(std::bit_cast<uint32_t>(blend.w[k]), std::bit_cast<uint32_t>(want_b[k]))
              << q.x << " " << q.y;
          ASSERT_TRUE(blend.lr[k] == mid.sample[want_corner[k]].lr);
        }
      }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 100);
}
}  // namespace proxima

namespace proxima {

// --match-extrapolate: under steady camera motion the walk starting from the offsets' last
// change continued is shorter and ends at the same matches as the plain warm start.
namespace {

// The floor mirror's key frame and the offsets of three equal camera steps from it: frames
// 1 and 2 (searched with `options`) are the warm starts of frame 3.
struct SteadySteps {
  ReflectionDepthImage key;
  OffsetBuffer o1, o2;
};
SteadySteps steady_steps(const BestMatchOptions& options) {
  const Scene scene = floor_mirror(false);
  RayScene rays(scene);
  const ReflectionFrame frame = frame_at(scene, kKeyEye);
  SteadySteps s{make_reflection_depth_image(frame, trace_reflections(scene, rays, frame), 1e3f), {}, {}};
  s.o1 = best_match_search(s.key, kKeyEye + kMove, nullptr, options);
  s.o2 = best_match_search(s.key, kKeyEye + 2.0f * kMove, &s.o1, options);
  return s;
}

}  // namespace

TEST(TemporalReflections, ExtrapolatedWarmStartShortensTheWalkAndKeepsTheMatches) {
  BestMatchOptions plain, extrapolated;
  extrapolated.extrapolate = true;
  const auto [key, o1, o2] = steady_steps(plain);
  BestMatchStats st_plain, st_ex;
  const OffsetBuffer a = best_match_search(key, kKeyEye + 3.0f * kMove, &o2, plain, &st_plain);
  const OffsetBuffer b = best_match_search(key, kKeyEye + 3.0f * kMove, &o2, extrapolated, &st_ex, &o1);
  ASSERT_GT(st_plain.searched, 2000u);
  // Each frame moves the matches by several pixels: the plain walk has work to save.
  EXPECT_GT(double(st_plain.steps), 2.0 * double(st_plain.searched));
  EXPECT_LT(double(st_ex.steps), 0.5 * double(st_plain.steps));
  size_t both = 0, same = 0;
  float worst = 0.0f;
  for (size_t i = 0; i < a.valid.size(); ++i) {
    if (!a.valid[i] || !b.valid[i]) continue;
    ++both;
    const float d = glm::length(a.offset[i] - b.offset[i]);
    worst = std::max(worst, d);
    same += d < 1e-4f;
  }
  EXPECT_GT(double(both), 0.98 * double(st_plain.searched - st_plain.invalid));
  EXPECT_GT(double(same), 0.99 * double(both)) << "worst " << worst << " px";
  EXPECT_LE(worst, 1.0f);
  // Without `earlier` the option changes nothing.
  const OffsetBuffer c = best_match_search(key, kKeyEye + 3.0f * kMove, &o2, extrapolated);
  EXPECT_EQ(c.offset, a.offset);
  EXPECT_EQ(c.valid, a.valid);
}

}  // namespace proxima

namespace proxima {

// best_match_search_into over a reused buffer (stale entries, or another size) writes every
// reflective entry as best_match_search does, warm-started and extrapolated too.
TEST(TemporalReflections, BestMatchIntoAReusedBufferMatchesAFreshSearch) {
  BestMatchOptions ex;
  ex.extrapolate = true;
  const auto [key, o1, o2] = steady_steps(ex);
  BestMatchStats st_fresh, st_reused;
  const OffsetBuffer fresh = best_match_search(key, kKeyEye + 3.0f * kMove, &o2, ex, &st_fresh, &o1);
  OffsetBuffer reused = o1;  // an older frame's offsets, scribbled over
  std::fill(reused.offset.begin(), reused.offset.end(), vec2(1e6f, -3.5f));
  std::fill(reused.valid.begin(), reused.valid.end(), uint8_t(1));
  best_match_search_into(key, kKeyEye + 3.0f * kMove, &o2, ex, reused, &st_reused, &o1);
  ASSERT_GT(key.pixels.size(), 2000u);
  EXPECT_EQ(st_reused.steps, st_fresh.steps);
  EXPECT_EQ(st_reused.invalid, st_fresh.invalid);
  for (const uint32_t i : key.pixels) {
    ASSERT_EQ(reused.offset[i], fresh.offset[i]) << i;
    ASSERT_EQ(reused.valid[i], fresh.valid[i]) << i;
  }
  // Another size: resized, and then as fresh as best_match_search's (zero off the reflector).
  OffsetBuffer other;
  other.width = 3;
  other.height = 2;
  other.offset.assign(6, vec2(7.0f));
  other.valid.assign(6, 1);
  best_match_search_into(key, kKeyEye + kMove, nullptr, ex, other);
  EXPECT_EQ(other.width, o1.width);
  EXPECT_EQ(other.height, o1.height);
  EXPECT_EQ(other.offset, o1.offset);
  EXPECT_EQ(other.valid, o1.valid);
}

}  // namespace proxima
