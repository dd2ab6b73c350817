// The reflection frame shared by the reflection methods and its Embree pass over the same
// rays: the G-buffer and reflection rays of step 1 of the thesis' Algorithm 6 (§4.2), drawn
// exactly as render_reference's first bounce, and the blend base + s·reflected
// (LERP(p.rgb_d, p.rgb_n, p.s) ↔ combine_shading). Symbols ↔ variables: e ↔
// frame.camera.position, p.rgb_d ↔ frame.base, p.s / p.g ↔ frame.specular / gloss, p.n ↔
// frame.normal, p.rID ↔ frame.reflector, r_i ↔ frame.direction.
#include "proxima/reflect/reflection_frame.h"

#include <algorithm>
#include <cmath>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/scene/shading.h"

namespace proxima {

namespace {

constexpr size_t kSampleGrain = 256;

void validate(const ReflectionOptions& o) {
  if (o.supersample < 1 || o.supersample > 8) fail_input("reflections: supersample must be in 1..8");
  if (o.glossy_rays < 1 || o.glossy_rays > 1024) fail_input("reflections: glossy rays must be in 1..1024");
  if (o.area_light_samples < 1 || o.area_light_samples > 64)
    fail_input("reflections: area light samples must be in 1..64");
  if (!(o.lobe_seed_cell >= 0.0f) || !std::isfinite(o.lobe_seed_cell))
    fail_input("reflections: lobe seed cell must be finite and >= 0");
}

// Seed of the world-space cell (edge `cell`) that holds `p`: the same in every frame.
uint64_t surface_cell_seed(uint64_t seed, vec3 p, float cell) {
  auto q = [&](float v) { return uint64_t(int64_t(std::clamp(std::floor(double(v) / double(cell)), -9e18, 9e18))); };
  return derive_seed(seed ^ 0x5EEDCE11ull, q(p.x), q(p.y), q(p.z));
}

// Two-sided surface as seen from `toward_viewer` (as trace/'s surface_point).
struct Facing {
  vec3 ng, n;
};
Facing facing(const Scene& scene, uint32_t triangle, float u, float v, vec3 toward_viewer) {
  Facing f;
  f.ng = triangle_normal(scene, triangle);
  if (glm::dot(f.ng, toward_viewer) < 0.0f) f.ng = -f.ng;
  f.n = shading_normal(scene, triangle, u, v);
  if (glm::dot(f.n, f.ng) < 0.0f) f.n = -f.n;
  return f;
}

}  // namespace

vec3 shade_reflected_point(const Scene& scene, uint32_t triangle, float u, float v, vec3 toward_viewer,
                           int area_light_samples) {
  const Material& m = scene.materials[scene.triangle_material[triangle]];
  const Facing f = facing(scene, triangle, u, v, toward_viewer);
  const vec3 p = triangle_point(scene, triangle, u, v);
  ShadingTerms terms;
  terms.emission = m.emission;
  terms.ambient = scene.ambient;
  terms.albedo = surface_diffuse(scene, triangle, u, v);
  terms.specular = m.specular;
  if (m.specular < 1.0f && terms.albedo != vec3(0.0f)) {
    for (const PointLight& light : scene.point_lights) terms.direct_irradiance += point_light_irradiance(light, p, f.n);
    const int n = area_light_samples;
    for (const AreaLight& light : scene.area_lights) {
      vec3 sum(0.0f);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          vec2 ab = stratum_sample(i, j, n, 0.5f, 0.5f);
          sum += area_light_sample_irradiance(light, light.point(ab.x, ab.y), p, f.n);
        }
      terms.direct_irradiance += sum / float(n * n);
    }
  }
  return combine_shading(terms);
}

ReflectionFrame prepare_reflection_frame(const Scene& scene, const Camera& camera, const ReflectionOptions& options,
                                         std::span<const Bounds3> object_bounds) {
  validate(options);
  validate_camera(camera, "reflection camera");
  Stopwatch watch;
  ReflectionFrame frame;
  const int k = options.supersample;
  frame.camera = camera;
  frame.supersample = k;
  frame.area_light_samples = options.area_light_samples;
  frame.sample_camera = camera;
  frame.sample_camera.width = camera.width * k;
  frame.sample_camera.height = camera.height * k;
  validate_camera(frame.sample_camera, "reflection camera × supersample");
  frame.scene_diagonal = std::max(scene_bounds(scene).diagonal(), 1e-3f);
  const float epsilon = kReflectionRayOffset * frame.scene_diagonal;

  // Step 1: G-buffer from e.
  RasterOptions ro;
  ro.outputs = kRasterDepth | kRasterTriangle | kRasterBarycentric | kRasterObject;
  ro.object_bounds = object_bounds;
  RasterImages g = rasterize(scene, frame.sample_camera, ro);
  const int sw = frame.sample_camera.width, sh = frame.sample_camera.height;
  const Camera& sc = frame.sample_camera;
  frame.base = ImageF(sw, sh, 3, 0.0f);
  parallel_for(size_t(sh), 8, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < sw; ++x) {
        uint32_t t = g.triangle.at(x, y);
        vec3 dir = ray_through(sc, vec2(float(x) + 0.5f, float(y) + 0.5f)).dir;
        vec3 c = t == kNoTriangle ? environment_radiance(scene.environment, dir)
                                  : shade_reflected_point(scene, t, g.barycentric.at(x, y, 0),
                                                          g.barycentric.at(x, y, 1), -dir, options.area_light_samples);
        for (int ch = 0; ch < 3; ++ch) frame.base.at(x, y, ch) = c[ch];
      }
  });

  // Reflective samples in row-major order, and their ray counts.
  for (int y = 0; y < sh; ++y)
    for (int x = 0; x < sw; ++x) {
      uint32_t t = g.triangle.at(x, y);
      if (t == kNoTriangle) continue;
      const Material& m = scene.materials[scene.triangle_material[t]];
      if (!m.reflective()) continue;
      frame.pixel.push_back(uint32_t(y) * uint32_t(sw) + uint32_t(x));
      frame.reflector.push_back(g.object.at(x, y));
      frame.specular.push_back(m.specular);
      frame.gloss.push_back(m.gloss);
    }
  const size_t n = frame.pixel.size();
  frame.first_ray.assign(n + 1, 0);
  for (size_t i = 0; i < n; ++i)
    frame.first_ray[i + 1] = frame.first_ray[i] + (glossy_lobe_half_angle(frame.gloss[i]) > 0.0f ? options.glossy_rays : 1);
  frame.position.resize(n);
  frame.normal.resize(n);
  frame.origin.resize(n);
  frame.direction.resize(frame.first_ray[n]);

  // The rays of render_reference's first bounce, from the same random streams.
  const float cell = options.lobe_seed_cell * frame.scene_diagonal;
  parallel_for(n, kSampleGrain, [&](size_t b, size_t e) {
    std::vector<vec2> lobe(size_t(options.glossy_rays));
    for (size_t i = b; i < e; ++i) {
      const int x = int(frame.pixel[i] % uint32_t(sw)), y = int(frame.pixel[i] / uint32_t(sw));
      const uint32_t t = g.triangle.at(x, y);
      const float u = g.barycentric.at(x, y, 0), v = g.barycentric.at(x, y, 1);
      const vec3 dir = glm::normalize(ray_through(sc, vec2(float(x) + 0.5f, float(y) + 0.5f)).dir);
      const Facing f = facing(scene, t, u, v, -dir);
      frame.position[i] = triangle_point(scene, t, u, v);
      frame.normal[i] = f.n;
      frame.origin[i] = frame.position[i] + epsilon * f.ng;
      const uint64_t out_pixel = uint64_t(y / k) * uint64_t(camera.width) + uint64_t(x / k);
      Pcg32 rng(cell > 0.0f ? surface_cell_seed(options.seed, frame.position[i], cell)
                            : derive_seed(options.seed, out_pixel, uint64_t((y % k) * k + (x % k))));
      // The reference draws its area-light jitter at this point before the lobe samples.
      if (frame.specular[i] < 1.0f && surface_diffuse(scene, t, u, v) != vec3(0.0f))
        for (size_t l = 0; l < scene.area_lights.size(); ++l)
          for (int s = 0; s < 2 * options.area_light_samples * options.area_light_samples; ++s) rng.next_float();
      const vec3 mirror = reflect(dir, f.n);
      const float half_angle = glossy_lobe_half_angle(frame.gloss[i]);
      vec3* out = &frame.direction[frame.first_ray[i]];
      if (half_angle > 0.0f) {
        stratified_samples_2d(lobe, rng);
        for (size_t r = 0; r < lobe.size(); ++r) out[r] = glossy_lobe_direction(mirror, f.ng, half_angle, lobe[r]);
      } else {
        out[0] = glossy_lobe_direction(mirror, f.ng, 0.0f, vec2(0.0f));
      }
    }
  });
  frame.ms = watch.elapsed_ms();
  return frame;
}

namespace {

// Sample i's mean radiance over its rays, in ray order; with `hits`, each ray's closest hit
// (left as it is where the ray escapes). One kernel for every trace entry: the same bits.
template <bool kHits>
vec3 trace_sample(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame, size_t i,
                  TracedReflections* hits) {
  vec3 sum(0.0f);
  for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r) {
    const vec3 dir = frame.direction[r];
    Hit hit = rays.intersect(Ray{frame.origin[i], dir, 0.0f, kInf});
    if (hit.valid()) {
      if constexpr (kHits) hits->hit_triangle[r] = hit.triangle, hits->hit_t[r] = hit.t;
      sum += shade_reflected_point(scene, hit.triangle, hit.u, hit.v, -dir, frame.area_light_samples);
    } else {
      sum += environment_radiance(scene.environment, dir);
    }
  }
  return sum / float(frame.first_ray[i + 1] - frame.first_ray[i]);
}

}  // namespace

TracedReflections trace_reflections(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame) {
  TracedReflections out;
  trace_reflections_into(scene, rays, frame, out);
  return out;
}

void trace_reflections_into(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                            TracedReflections& out) {
  Stopwatch watch;
  const size_t n = frame.sample_count();
  out.radiance.resize(n);  // every sample is written below
  out.hit_triangle.assign(frame.direction.size(), kNoTriangle);
  out.hit_t.assign(frame.direction.size(), kInf);
  parallel_for(n, kSampleGrain, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) out.radiance[i] = trace_sample<true>(scene, rays, frame, i, &out);
  });
  out.ms = watch.elapsed_ms();
}

void trace_reflection_samples(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                              std::span<const uint32_t> samples, std::span<vec3> radiance) {
  parallel_for(samples.size(), kSampleGrain, [&](size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) radiance[samples[k]] = trace_sample<false>(scene, rays, frame, samples[k], nullptr);
  });
}

ImageF compose_reflections(const ReflectionFrame& frame, std::span<const vec3> reflected) {
  ImageF samples = frame.base;
  for (size_t i = 0; i < frame.sample_count(); ++i) {
    const int sw = frame.sample_camera.width;
    const int x = int(frame.pixel[i] % uint32_t(sw)), y = int(frame.pixel[i] / uint32_t(sw));
    for (int c = 0; c < 3; ++c) samples.at(x, y, c) += frame.specular[i] * reflected[i][c];
  }
  const int k = frame.supersample, w = frame.camera.width, h = frame.camera.height;
  ImageF out(w, h, 3, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        float sum = 0.0f;
        for (int j = 0; j < k; ++j)
          for (int i = 0; i < k; ++i) sum += samples.at(x * k + i, y * k + j, c);
        out.at(x, y, c) = sum / float(k * k);
      }
  return out;
}

ImageU8 reflective_pixel_mask(const ReflectionFrame& frame) {
  ImageU8 mask(frame.camera.width, frame.camera.height, 1, 0);
  const int sw = frame.sample_camera.width, k = frame.supersample;
  for (uint32_t px : frame.pixel) mask.at(int(px % uint32_t(sw)) / k, int(px / uint32_t(sw)) / k) = 1;
  return mask;
}

}  // namespace proxima