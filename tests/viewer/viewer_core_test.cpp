// The viewer's platform-independent parts: fly camera, bitmap font, input
// scripts, camera recording, the reference's row bands.
#include <gtest/gtest.h>

#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/load.h"
#include "proxima/trace/reference_renderer.h"
#include "proxima/viewer/bitmap_font.h"
#include "proxima/viewer/camera_recording.h"
#include "proxima/viewer/fly_camera.h"
#include "proxima/viewer/view_script.h"
#include "test_util.h"

namespace proxima {
namespace {

TEST(FlyCamera, StartsWhereTheCameraLooks) {
  const Camera c = look_at({1, 2, 3}, {4, 1, -2}, {0, 1, 0}, 50.0f, 64, 32);
  const FlyCamera fly = fly_camera_from(c, 2.0f);
  EXPECT_NEAR(glm::distance(fly_forward(fly), camera_forward(c)), 0.0f, 1e-5f);
  const Camera back = fly_to_camera(fly, 64, 32);
  EXPECT_NEAR(glm::distance(camera_forward(back), camera_forward(c)), 0.0f, 1e-5f);
  EXPECT_EQ(back.position, c.position);
  EXPECT_EQ(back.vfov_deg, 50.0f);
}

TEST(FlyCamera, WasdMovesOnTheFloorPlaneAtTheSpeed) {
  FlyCamera fly = fly_camera_from(look_at({0, 1, 0}, {0, 0, -1}, {0, 1, 0}, 60.0f, 8, 8), 2.0f);  // looks down-ahead
  FlyInput in;
  in.forward = true;
  EXPECT_TRUE(update_fly_camera(fly, in, 0.5f));
  EXPECT_NEAR(fly.position.x, 0.0f, 1e-5f);
  EXPECT_NEAR(fly.position.y, 1.0f, 1e-5f);  // looking down does not sink the camera
  EXPECT_NEAR(fly.position.z, -1.0f, 1e-5f);
  in = {};
  in.right = true;
  update_fly_camera(fly, in, 0.5f);
  EXPECT_NEAR(fly.position.x, 1.0f, 1e-5f);
  in = {};
  EXPECT_FALSE(update_fly_camera(fly, in, 0.5f));  // no input, no change
}

TEST(FlyCamera, MouseTurnsAndPitchStopsShortOfThePoles) {
  FlyCamera fly;
  FlyInput in;
  in.mouse_px = {450.0f, 0.0f};  // 90° right at 0.2°/px
  update_fly_camera(fly, in, 0.0f);
  EXPECT_NEAR(glm::distance(fly_forward(fly), vec3(1, 0, 0)), 0.0f, 1e-5f);
  in.mouse_px = {0.0f, -10000.0f};
  update_fly_camera(fly, in, 0.0f);
  EXPECT_EQ(fly.pitch_deg, 89.0f);
  in = {};
  in.scroll = 1000.0f;
  update_fly_camera(fly, in, 0.0f);
  EXPECT_EQ(fly.speed, kMaxFlySpeed);
}

TEST(BitmapFont, DrawsInsideItsBoxOnly) {
  ImageU8 img(40, 20, 4, 0);
  const int w = draw_text(img, 2, 3, "Ab", {255, 0, 0, 255});
  EXPECT_EQ(w, 2 * kGlyphWidth);
  EXPECT_EQ(text_width("Ab\nxyz"), 3 * kGlyphWidth);
  EXPECT_EQ(text_height("Ab\nxyz"), 2 * kGlyphHeight);
  int lit = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      if (img.at(x, y, 0)) {
        ++lit;
        EXPECT_TRUE(x >= 2 && x < 2 + w && y >= 3 && y < 3 + kGlyphHeight) << x << "," << y;
      }
  EXPECT_GT(lit, 20);
  draw_text(img, 38, 18, "\x01\xff~", {1, 1, 1, 1}, 3);  // clipped, unprintable: no crash
}

TEST(ViewScript, ExpandsTokensIntoFrames) {
  const auto frames = parse_view_script("shot:a.png,hold:w:3,press:2,shot:b:c.png,idle:2,mouse:5:-1,resize:100:50,quit");
  ASSERT_EQ(frames.size(), 3u + 1u + 2u + 1u + 1u + 1u);
  EXPECT_EQ(frames[0].shots, std::vector<std::string>{"a.png"});
  ASSERT_EQ(frames[0].before.size(), 1u);
  EXPECT_EQ(frames[0].before[0].type, ViewEvent::Type::KeyDown);
  EXPECT_EQ(frames[0].before[0].key, "w");
  EXPECT_TRUE(frames[1].before.empty());
  ASSERT_EQ(frames[2].after.size(), 1u);
  EXPECT_EQ(frames[2].after[0].type, ViewEvent::Type::KeyUp);
  EXPECT_EQ(frames[3].before.size(), 2u);
  EXPECT_EQ(frames[3].shots, std::vector<std::string>{"b:c.png"});
  EXPECT_EQ(frames[6].before[0].value, vec2(5, -1));
  EXPECT_EQ(frames[7].before[0].type, ViewEvent::Type::Resize);
  EXPECT_EQ(frames[8].before[0].type, ViewEvent::Type::Quit);
}

TEST(ViewScript, BadTokensNameTheFlagAndToken) {
  for (const char* bad : {"jump", "hold:w", "hold:w:0", "idle:x", "mouse:1", "resize:5:5", "press:", "shot:"}) {
    const std::string e = error_of([&] { parse_view_script(bad); });
    EXPECT_NE(e.find("--script"), std::string::npos) << bad << ": " << e;
  }
}

TEST(CameraRecording, WritesASceneFileTheCommandsRead) {
  TempDir dir;
  CameraRecorder r;
  FlyCamera fly = fly_camera_from(look_at({0, 1.5f, 2}, {0, 1, 0}, {0, 1, 0}, 55.0f, 8, 8), 1.0f);
  record_camera(r, fly, 0.1f, false);  // the first key always
  record_camera(r, fly, 0.1f, false);  // unchanged: none
  fly.position.x += 0.5f;
  record_camera(r, fly, 0.1f, true);
  ASSERT_EQ(r.path.keys.size(), 2u);
  const auto file = dir.path / "path.json";
  write_recorded_path(file, "cornell", r);
  const Scene s = load_scene(file.string());
  ASSERT_EQ(s.camera_paths.size(), 1u);
  EXPECT_EQ(s.camera_paths[0].name, kRecordedPathName);
  ASSERT_EQ(s.camera_paths[0].keys.size(), 2u);
  EXPECT_NEAR(s.camera_paths[0].keys[1].position.x, 0.5f, 1e-5f);
  EXPECT_NEAR(s.camera_paths[0].keys[1].time, 0.2f, 1e-5f);
  EXPECT_EQ(s.triangles.size(), make_builtin_scene("cornell").triangles.size());
}

TEST(ReferenceRows, BandsAreTheFullImagesRows) {
  const Scene scene = make_builtin_scene("room-reflector");
  const RayScene rays(scene);
  Camera cam = scene.cameras.at(0).camera;
  cam.width = 24;
  cam.height = 17;
  ReferenceOptions o;
  o.area_light_samples = 2;
  o.glossy_rays = 2;
  const ImageF full = render_reference(scene, rays, cam, o);
  ImageF bands(cam.width, cam.height, 3, 0.0f);
  for (int y0 = 0; y0 < cam.height; y0 += 5) {
    o.row_begin = y0;
    o.row_end = y0 + 5;
    const ImageF part = render_reference(scene, rays, cam, o);
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x)
        for (int c = 0; c < 3; ++c)
          if (y >= y0 && y < y0 + 5) bands.at(x, y, c) = part.at(x, y, c);
          else EXPECT_EQ(part.at(x, y, c), 0.0f);
  }
  EXPECT_TRUE(bands == full);
  o.row_begin = 3;
  o.row_end = 2;
  EXPECT_NE(error_of([&] { render_reference(scene, rays, cam, o); }), "");
}

}  // namespace
}  // namespace proxima
