// Degenerate geometry straight into the renderers, bypassing sanitize_scene: a
// Scene built through the library API may hold what load_scene would drop or refuse.
// Zero-area, collinear, duplicate, NaN and Inf triangles at scales 1e-6 … 1e6 go through
// the rasterizer, the Embree item buffer and the reference renderer without a crash; the
// degenerate ones never cover a pixel, the valid quad does, and every output is finite.
// docs/robustness.md lists what happens to each kind.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "proxima/core/camera.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"
#include "trace/test_geometry.h"

namespace proxima {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Triangles 0, 1: a unit quad (scaled by `s`, moved by `o`) facing +z. 2: a copy of 0.
// 3: zero area (repeated vertex). 4: collinear. 5: a NaN vertex. 6: an Inf vertex.
Scene degenerate_scene(float s, vec3 o) {
  Scene scene;
  scene.name = "degenerate";
  const uint32_t mat = test::add_diffuse(scene, vec3(0.7f));
  Mesh quad = test::quad_mesh(o + s * vec3(-0.5f, -0.5f, 0), vec3(s, 0, 0), vec3(0, s, 0));
  add_object(scene, quad, "quad", mat);
  Mesh bad;
  const vec3 n(0, 0, 1);
  auto tri = [&](vec3 a, vec3 b, vec3 c) {
    const uint32_t i = uint32_t(bad.positions.size());
    for (vec3 p : {a, b, c}) {
      bad.positions.push_back(p);
      bad.normals.push_back(n);
      bad.uvs.push_back(vec2(0));
    }
    bad.triangles.push_back(uvec3(i, i + 1, i + 2));
  };
  const vec3 p0 = quad.positions[0], p1 = quad.positions[1], p2 = quad.positions[2];
  tri(p0, p1, p2);                                        // duplicate of triangle 0
  tri(p0, p0, p2);                                        // zero area
  tri(p0, 0.5f * (p0 + p2), p2);                          // collinear
  tri(p0, p1, vec3(kNaN, p2.y, p2.z));                    // NaN
  tri(p0, vec3(p1.x, kInf, p1.z), p2);                    // Inf
  add_object(scene, bad, "degenerate", mat);
  PointLight light;
  light.position = o + s * vec3(0.3f, 0.4f, 2.0f);
  light.intensity = vec3(s * s * 4.0f);
  scene.point_lights.push_back(light);
  return scene;
}

bool degenerate_id(uint32_t id) { return id >= 3 && id <= 6; }

TEST(DegenerateGeometry, RasterTraceAndRenderAtEveryScale) {
  struct Case {
    float scale;
    vec3 offset;
  };
  for (const Case c : {Case{1e-6f, vec3(0)}, Case{1.0f, vec3(0)}, Case{1e6f, vec3(0)}, Case{1.0f, vec3(1e6f, -1e6f, 1e6f)},
                       Case{1e3f, vec3(1e6f)}}) {
    SCOPED_TRACE("scale " + std::to_string(c.scale) + " offset " + std::to_string(c.offset.x));
    const Scene scene = degenerate_scene(c.scale, c.offset);
    const vec3 eye = c.offset + c.scale * vec3(0.1f, 0.05f, 2.0f);
    const Camera cam = look_at(eye, c.offset, vec3(0, 1, 0), 50.0f, 32, 24, 0.1f * c.scale, 10.0f * c.scale);

    RasterStats stats;
    const RasterImages raster = rasterize(scene, cam, {}, &stats);
    const RayScene rays(scene);
    const ItemBuffer items = trace_item_buffer(scene, rays, cam);
    ReferenceOptions options;
    options.area_light_samples = 1;
    options.glossy_rays = 1;
    const ImageF color = render_reference(scene, rays, cam, options);

    int raster_hits = 0, trace_hits = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const uint32_t r = raster.triangle.at(x, y), t = items.triangle.at(x, y);
        EXPECT_FALSE(degenerate_id(r)) << "raster pixel " << x << "," << y << " shows triangle " << r;
        EXPECT_FALSE(degenerate_id(t)) << "trace pixel " << x << "," << y << " shows triangle " << t;
        raster_hits += r != kNoTriangle;
        trace_hits += t != kNoTriangle;
        if (r != kNoTriangle) {
          EXPECT_TRUE(std::isfinite(raster.depth.at(x, y)));
        }
        if (t != kNoTriangle) {
          EXPECT_TRUE(std::isfinite(items.depth.at(x, y)));
        }
        for (int ch = 0; ch < 3; ++ch) ASSERT_TRUE(std::isfinite(color.at(x, y, ch))) << x << "," << y;
      }
    // The quad fills about a quarter of the view: both paths see it.
    EXPECT_GT(raster_hits, 32 * 24 / 8);
    EXPECT_GT(trace_hits, 32 * 24 / 8);
    EXPECT_LE(std::abs(raster_hits - trace_hits), 32 * 24 / 20);
  }
}

}  // namespace
}  // namespace proxima
