// The best match's AVX-512 path (detail::best_match_wide, runtime dispatch) against its SSE2
// path: bit for bit the same offsets, valid flags and statistics, cold, warm-started and
// extrapolated, on built-in scenes with several reflectors and their silhouettes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "proxima/reflect/temporal_reuse.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"

namespace proxima {
namespace {

struct WideOff {  // the SSE2 path for the scope
  WideOff() { detail::best_match_wide = false; }
  ~WideOff() { detail::best_match_wide = true; }
};

void expect_same_bits(const OffsetBuffer& a, const OffsetBuffer& b) {
  ASSERT_EQ(a.offset.size(), b.offset.size());
  EXPECT_EQ(std::memcmp(a.offset.data(), b.offset.data(), a.offset.size() * sizeof(vec2)), 0);
  EXPECT_EQ(a.valid, b.valid);
}

void expect_same_stats(const BestMatchStats& a, const BestMatchStats& b) {
  EXPECT_EQ(a.searched, b.searched);
  EXPECT_EQ(a.invalid, b.invalid);
  EXPECT_EQ(a.steps, b.steps);
}

class BestMatchWide : public ::testing::TestWithParam<const char*> {};

TEST_P(BestMatchWide, SameBitsAsTheSsePath) {
  if (!detail::best_match_wide_available()) GTEST_SKIP() << "no AVX-512 on this CPU, or an unoptimized build (SSE2 only)";
  const Scene scene = make_builtin_scene(GetParam());
  RayScene rays(scene);
  const CameraPath& path = scene.camera_paths.front();
  const float t0 = path.keys.front().time, t1 = path.keys.back().time;
  const float far = scene_far_plane(scene);
  ReflectionOptions ro;
  ro.supersample = 1;
  ro.glossy_rays = 2;
  auto frame = [&](int f) {
    const float t = t0 + float(f) * (t1 - t0) / 99.0f;  // 100 frames on the path: big steps
    return prepare_reflection_frame(scene, camera_at_time(path, t, 96, 72, 0.01f, far), ro);
  };
  const ReflectionFrame key_frame = frame(20);
  const ReflectionDepthImage key =
      make_reflection_depth_image(key_frame, trace_reflections(scene, rays, key_frame), 1e3f);
  ASSERT_GT(key.pixels.size(), 100u);
  BestMatchOptions plain, ex;
  ex.extrapolate = true;
  ex.max_steps = 2;  // some walks run out: INVALID ends compared too
  OffsetBuffer wide[3], narrow[3];
  uint64_t steps = 0, invalid = 0;
  for (const BestMatchOptions& options : {plain, ex}) {
    for (int k = 0; k < 3; ++k) {
      const vec3 eye = frame(21 + 2 * k).camera.position;
      const OffsetBuffer* previous = k > 0 ? &wide[k - 1] : nullptr;
      const OffsetBuffer* earlier = k > 1 ? &wide[k - 2] : nullptr;
      BestMatchStats sw, sn;
      wide[k] = best_match_search(key, eye, previous, options, &sw, earlier);
      {
        const WideOff off;
        narrow[k] = best_match_search(key, eye, k > 0 ? &narrow[k - 1] : nullptr, options, &sn,
                                      k > 1 ? &narrow[k - 2] : nullptr);
      }
      SCOPED_TRACE(k);
      expect_same_bits(wide[k], narrow[k]);
      expect_same_stats(sw, sn);
      steps += sw.steps;
      invalid += sw.invalid;
    }
  }
  EXPECT_GT(steps, 0u);  // walks, and INVALID ends, to compare
  EXPECT_GT(invalid, 0u);
}

INSTANTIATE_TEST_SUITE_P(TemporalReflections, BestMatchWide, ::testing::Values("living-room", "bathroom"));

}  // namespace
}  // namespace proxima
