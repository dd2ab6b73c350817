// ViewerSession headless: resolution scaling while moving, refinement when
// still, the progressive reference's error, technique switches, bad keys and resizes.
#include <gtest/gtest.h>

#include "proxima/scene/builtin_scenes.h"
#include "proxima/viewer/viewer_session.h"

namespace proxima {
namespace {

// A small window on room-reflector (2k-triangle mirror in a room: every technique runs).
ViewerSession small_session(ViewerOptions o = {}) {
  Scene scene = make_builtin_scene("room-reflector");
  const Camera start = scene.cameras.at(0).camera;
  o.move_scale = o.move_scale ? o.move_scale : 2;
  o.techniques.cube_size = 32;
  o.techniques.occluder_resolution = 64;
  o.techniques.shadow_map_resolution = 64;
  o.techniques.shadow_light_samples = 2;
  o.techniques.reference.glossy_rays = 2;
  o.techniques.reference.area_light_samples = 2;
  return ViewerSession(std::move(scene), start, 48, 32, o);
}

int index_of(const ViewerSession& s, const std::string& name) {
  for (size_t i = 0; i < s.techniques().size(); ++i)
    if (s.techniques()[i].name == name) return int(i);
  return -1;
}

TEST(ViewerSession, ScalesDownWhileMovingAndRefinesWhenStill) {
  ViewerSession s = small_session();
  const ImageU8& first = s.frame(0.03f);
  EXPECT_EQ(first.width(), 48);
  EXPECT_EQ(first.height(), 32);
  EXPECT_FALSE(s.status().moving);
  EXPECT_TRUE(s.status().refined);
  EXPECT_EQ(s.status().render_width, 48);
  s.key_down("w");
  s.frame(0.03f);
  EXPECT_TRUE(s.status().moving);
  EXPECT_EQ(s.status().render_width, 24);
  EXPECT_EQ(s.status().render_height, 16);
  EXPECT_LT(s.status().error_mae, 0.0);  // no error while moving
  s.key_up("w");
  s.frame(0.03f);
  EXPECT_FALSE(s.status().moving);
  EXPECT_EQ(s.status().render_width, 48);
  // The reference builds up band by band; then the error is known and plausible.
  for (int i = 0; i < 100 && s.status().error_mae < 0.0; ++i) s.frame(0.03f);
  EXPECT_EQ(s.status().reference_progress, 1.0);
  EXPECT_GE(s.status().error_mae, 0.0);
  EXPECT_LT(s.status().error_mae, 60.0);
}

TEST(ViewerSession, SwitchingTechniquesChangesTheImage) {
  ViewerOptions o;
  o.overlay = false;  // compare the renders, not the panel
  ViewerSession s = small_session(o);
  const ImageU8 reference = s.frame(0.03f);
  s.key_down("3");  // rectified env map
  s.key_up("3");
  EXPECT_EQ(s.techniques()[size_t(s.status().technique)].name, "rectified");
  const ImageU8 rectified = s.frame(0.03f);
  EXPECT_FALSE(rectified == reference);
  size_t differing = 0;
  for (size_t i = 0; i < reference.data().size(); ++i) differing += reference.data()[i] != rectified.data()[i];
  EXPECT_GT(differing, 10u);
  // Every available technique renders a frame of the window's size, moving and still.
  for (size_t i = 0; i < s.techniques().size(); ++i) {
    if (!s.techniques()[i].unavailable.empty()) continue;
    ASSERT_TRUE(s.select_technique(int(i))) << s.techniques()[i].name;
    s.mouse_motion({4.0f, 1.0f});
    EXPECT_EQ(s.frame(0.03f).width(), 48) << s.techniques()[i].name;
    EXPECT_TRUE(s.status().moving);
    EXPECT_FALSE(s.status().steps.empty()) << s.techniques()[i].name;
    s.frame(0.03f);
    EXPECT_TRUE(s.status().refined) << s.techniques()[i].name;
  }
}

TEST(ViewerSession, BadKeysUnavailableSlotsAndResizesDoNotBreakIt) {
  ViewerSession s = small_session();
  s.frame(0.03f);
  const int before = s.status().technique;
  for (const char* key : {"", "f13", "0", "\xff", "backspace", "Ü"}) s.key_down(key), s.key_up(key);
  EXPECT_EQ(s.status().technique, before);
  const int gibr = index_of(s, "gibr");
  ASSERT_GE(gibr, 0);
  EXPECT_FALSE(s.techniques()[size_t(gibr)].unavailable.empty());
  EXPECT_FALSE(s.select_technique(gibr));
  EXPECT_NE(s.status().message.find("GIBR"), std::string::npos);
  EXPECT_FALSE(s.select_technique(99));
  s.key_down("tab");  // next available
  EXPECT_NE(s.status().technique, before);
  s.resize(20, 70);
  EXPECT_EQ(s.frame(0.03f).width(), 20);
  EXPECT_EQ(s.frame(0.03f).height(), 70);
  s.resize(0, -5);  // clamped
  EXPECT_EQ(s.frame(0.03f).width(), 16);
  s.mouse_motion({NAN, 1.0f});
  s.scroll(INFINITY);
  s.frame(0.03f);
  EXPECT_TRUE(std::isfinite(s.fly().yaw_deg));
  EXPECT_TRUE(std::isfinite(s.fly().speed));
  EXPECT_FALSE(s.quit_requested());
  s.key_down("escape");
  EXPECT_TRUE(s.quit_requested());
}

TEST(ViewerSession, ParameterKeysChangeTheTechniquesKnob) {
  ViewerOptions o;
  o.overlay = false;
  ViewerSession s = small_session(o);
  s.select_technique(index_of(s, "rectified"));
  const ImageU8 before = s.frame(0.03f);  // cube map 32²
  s.key_down("=");
  EXPECT_EQ(s.status().message, "cube map faces 64");
  EXPECT_FALSE(s.status().refined);
  const ImageU8 after = s.frame(0.03f);
  EXPECT_FALSE(before == after);  // a finer map shows finer reflections
  s.key_down("-");
  s.key_down("-");
  EXPECT_EQ(s.status().message, "cube map faces 16");
  s.key_down("-");  // bounded
  EXPECT_EQ(s.status().message, "cube map faces 16");
  s.select_technique(index_of(s, "shadows"));
  s.key_down("=");
  EXPECT_NE(s.status().message.find("no parameter"), std::string::npos);
  s.select_technique(index_of(s, "reference"));
  s.key_down("=");
  EXPECT_EQ(s.status().message, "area-light samples n (n x n) 2");
  EXPECT_EQ(s.frame(0.03f).width(), 48);
}

TEST(ViewerSession, AdaptiveScaleCoarsensUnderATightBudget) {
  ViewerOptions o;
  o.move_scale = 0;
  o.move_budget_ms = 1e-6;  // nothing fits: the scale climbs to its maximum
  o.max_move_scale = 4;
  Scene scene = make_builtin_scene("cornell");
  const Camera start = scene.cameras.at(0).camera;
  ViewerSession s(std::move(scene), start, 64, 64, o);
  s.key_down("w");
  for (int i = 0; i < 6; ++i) s.frame(0.01f);
  EXPECT_EQ(s.status().scale, 4);
  EXPECT_EQ(s.status().render_width, 16);
}

}  // namespace
}  // namespace proxima
