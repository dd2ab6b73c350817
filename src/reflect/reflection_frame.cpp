// The reflection frame shared by the reflection methods and its Embree pass over the same
// rays: the G-buffer and reflection rays of step 1 of the thesis' Algorithm 6 (§4.2), drawn
// exactly as render_reference's first bounce, and the blend base + s·reflected
// (LERP(p.rgb_d, p.rgb_n, p.s) ↔ combine_shading). Symbols ↔ variables: e ↔
// frame.camera.position, p.rgb_d ↔ frame.base, p.s / p.g ↔ frame.specular / gloss, p.n ↔
// frame.normal, p.rID ↔ frame.reflector, r_i ↔ frame.direction.
#include "proxima/reflect/reflection_frame.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/hit_shading.h"
#include "proxima/scene/shading.h"
#include "shading_lanes.h"

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

// The view directions of ray_through with the camera's constants (focal length, half
// sizes) computed once: the same operations on the same values, so the same bits.
struct ViewRays {
  explicit ViewRays(const Camera& c)
      : orientation(c.orientation), f(focal_length_px(c)), half_w(0.5f * float(c.width)),
        half_h(0.5f * float(c.height)) {
    column.assign(round_up_lanes(size_t(c.width)), 0.0f);
    for (int x = 0; x < c.width; ++x) column[size_t(x)] = (float(x) + 0.5f - half_w) / f;
  }
  vec3 dir(int x, int y) const { return glm::normalize(orientation * vec3(column[size_t(x)], row(y), -1.0f)); }
  float row(int y) const { return (half_h - (float(y) + 0.5f)) / f; }
  // A row's directions are computed eight at a time: whole lane groups.
  static size_t round_up_lanes(size_t n) { return (n + 7) / 8 * 8; }
  quat orientation;
  float f, half_w, half_h;
  std::vector<float> column;  // per x: the camera-space x of dir(x, ·), padded with zeros
};

// The view directions of one row, per coordinate (padded to whole lane groups).
struct RowDirs {
  explicit RowDirs(const ViewRays& view) : x(view.column.size()), y(view.column.size()), z(view.column.size()) {}
  std::vector<float> x, y, z;
};

#if PROXIMA_SHADE_LANES
// ViewRays::dir of row y for every x, L::kWidth at a time: per lane glm's quaternion
// rotation (v + ((uv·w) + uuv)·2, uv = q × v, uuv = q × uv) and normalize (v · (1 / √(v·v)))
// in their order, so each lane gives dir's bits.
template <class L>
inline __attribute__((always_inline)) void view_dirs_lanes(const ViewRays& view, int y, RowDirs& out) {
  using V = typename L::V;
  const quat& q = view.orientation;
  const V qx = L::set1(q.x), qy = L::set1(q.y), qz = L::set1(q.z), qw = L::set1(q.w);
  const V dy = L::set1(view.row(y)), dz = L::set1(-1.0f), two = L::set1(2.0f), one = L::set1(1.0f);
  for (size_t i = 0; i < view.column.size(); i += L::kWidth) {
    const V dx = L::load(&view.column[i]);
    const V ux = L::sub(L::mul(qy, dz), L::mul(dy, qz));
    const V uy = L::sub(L::mul(qz, dx), L::mul(dz, qx));
    const V uz = L::sub(L::mul(qx, dy), L::mul(dx, qy));
    const V wx = L::sub(L::mul(qy, uz), L::mul(uy, qz));
    const V wy = L::sub(L::mul(qz, ux), L::mul(uz, qx));
    const V wz = L::sub(L::mul(qx, uy), L::mul(ux, qy));
    const V rx = L::add(dx, L::mul(L::add(L::mul(ux, qw), wx), two));
    const V ry = L::add(dy, L::mul(L::add(L::mul(uy, qw), wy), two));
    const V rz = L::add(dz, L::mul(L::add(L::mul(uz, qw), wz), two));
    const V inv = L::div(one, L::sqrt(L::dot(rx, ry, rz, rx, ry, rz)));
    L::store(&out.x[i], L::mul(rx, inv));
    L::store(&out.y[i], L::mul(ry, inv));
    L::store(&out.z[i], L::mul(rz, inv));
  }
}

#if PROXIMA_SHADE_AVX
__attribute__((target("avx"), flatten)) void view_dirs_avx(const ViewRays& view, int y, RowDirs& out) {
  view_dirs_lanes<Lanes8>(view, y, out);
}
#endif

void view_dirs(const ViewRays& view, int y, RowDirs& out) {
#if PROXIMA_SHADE_AVX
  if (has_avx()) return view_dirs_avx(view, y, out);
#endif
  view_dirs_lanes<Lanes4>(view, y, out);
}
#else
void view_dirs(const ViewRays& view, int y, RowDirs& out) {
  for (size_t x = 0; x < view.column.size(); ++x) {
    const vec3 d = view.dir(int(x), y);
    out.x[x] = d.x, out.y[x] = d.y, out.z[x] = d.z;
  }
}
#endif

// The G-buffer images prepare_reflection_frame rasterizes into, kept between calls (the
// rasterizer reuses an image of the right size in place): no fresh pages per frame. At most
// kPooledGBuffers of at most kPooledSamples samples each (12 bytes a sample), so the pool
// holds ≤ 100 MB whatever sizes a program renders.
constexpr size_t kPooledGBuffers = 2;
constexpr size_t kPooledSamples = size_t(2048) * 2048;
std::mutex g_gbuffer_mutex;
std::vector<RasterImages> g_gbuffers;

RasterImages take_gbuffer() {
  std::lock_guard<std::mutex> lock(g_gbuffer_mutex);
  if (g_gbuffers.empty()) return {};
  RasterImages g = std::move(g_gbuffers.back());
  g_gbuffers.pop_back();
  return g;
}

void return_gbuffer(RasterImages&& g) {
  if (size_t(g.triangle.width()) * size_t(g.triangle.height()) > kPooledSamples) return;
  std::lock_guard<std::mutex> lock(g_gbuffer_mutex);
  if (g_gbuffers.size() < kPooledGBuffers) g_gbuffers.push_back(std::move(g));
}

// Row y of `base`: per pixel what shade_reflected_point (or the environment) gives along the
// view ray.
void shade_base_row(const Scene& scene, const RasterImages& g, const ViewRays& view, int y, RowDirs& dirs,
                    HitShading& shading, ImageF& base) {
  const int sw = g.triangle.width();
  const uint32_t* tri = &g.triangle.at(0, y);
  const float* bary = &g.barycentric.at(0, y);
  float* out = &base.at(0, y);
  shading.clear();
  view_dirs(view, y, dirs);
  // The lanes must give dir()'s bits (a build that fuses multiply-adds in one and not the
  // other would not): one pixel of each row, a different column per row, is checked.
  const int cx = y % sw;
  const vec3 check = view.dir(cx, y);
  if (check != vec3(dirs.x[size_t(cx)], dirs.y[size_t(cx)], dirs.z[size_t(cx)]))
    throw std::logic_error("reflection frame: the lanes' view direction differs from the scalar one");
  for (int x = 0; x < sw; ++x) {
    const vec3 dir(dirs.x[size_t(x)], dirs.y[size_t(x)], dirs.z[size_t(x)]);
    if (tri[x] == kNoTriangle)
      shading.add_miss(environment_radiance(scene.environment, dir));
    else
      shading.add_hit(scene, tri[x], bary[2 * x], bary[2 * x + 1], -dir);
  }
  shading.finish();
  for (int x = 0; x < sw; ++x) {
    const vec3 c = shading.color[size_t(x)];
    out[3 * x] = c.x, out[3 * x + 1] = c.y, out[3 * x + 2] = c.z;
  }
}

}  // namespace

ReflectionFrame prepare_reflection_frame(const Scene& scene, const Camera& camera, const ReflectionOptions& options,
                                         std::span<const Bounds3> object_bounds) {
  ReflectionFrame frame;
  prepare_reflection_frame_into(scene, camera, options, frame, object_bounds);
  return frame;
}

void prepare_reflection_frame_into(const Scene& scene, const Camera& camera, const ReflectionOptions& options,
                                   ReflectionFrame& frame, std::span<const Bounds3> object_bounds) {
  validate(options);
  validate_camera(camera, "reflection camera");
  Stopwatch watch;
  const int k = options.supersample;
  Camera sample_camera = camera;
  sample_camera.width = camera.width * k;
  sample_camera.height = camera.height * k;
  validate_camera(sample_camera, "reflection camera × supersample");  // before `frame` changes
  frame.camera = camera;
  frame.supersample = k;
  frame.area_light_samples = options.area_light_samples;
  frame.sample_camera = sample_camera;
  frame.scene_diagonal = std::max(scene_bounds(scene).diagonal(), 1e-3f);
  const float epsilon = kReflectionRayOffset * frame.scene_diagonal;

  // Step 1: G-buffer from e (the object id is scene.triangle_object of the triangle).
  RasterOptions ro;
  ro.outputs = kRasterTriangle | kRasterBarycentric;
  ro.object_bounds = object_bounds;
  RasterImages g = take_gbuffer();
  rasterize(scene, frame.sample_camera, ro, g, AcceptAllFragments{});
  frame.raster_ms = watch.elapsed_ms();
  const int sw = frame.sample_camera.width, sh = frame.sample_camera.height;
  const ViewRays view(frame.sample_camera);
  const LightTable lights(scene, options.area_light_samples);
  if (frame.base.width() != sw || frame.base.height() != sh || frame.base.channels() != 3)
    frame.base = ImageF(sw, sh, 3, 0.0f);  // else every pixel is written below
  parallel_for(size_t(sh), 8, [&](size_t y0, size_t y1) {
    RowDirs dirs(view);
    HitShading shading(lights);
    for (int y = int(y0); y < int(y1); ++y) shade_base_row(scene, g, view, y, dirs, shading, frame.base);
  });
  frame.shading_ms = watch.elapsed_ms() - frame.raster_ms;

  // Reflective samples in row-major order, and their ray counts: counted per row, then
  // each row written at its offset (the same lists as one pass over the rows).
  // The material of a reflective sample's triangle, else nullptr.
  const auto reflective = [&](uint32_t t) -> const Material* {
    if (t == kNoTriangle) return nullptr;
    const Material& m = scene.materials[scene.triangle_material[t]];
    return m.reflective() ? &m : nullptr;
  };
  const auto rays_of = [&](const Material& m) {
    return uint32_t(glossy_lobe_half_angle(m.gloss) > 0.0f ? options.glossy_rays : 1);
  };
  std::vector<uint32_t> row_samples(size_t(sh) + 1, 0), row_rays(size_t(sh) + 1, 0);
  parallel_for(size_t(sh), 8, [&](size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y) {
      const uint32_t* tri = &g.triangle.at(0, int(y));
      uint32_t samples = 0, rays = 0;
      for (int x = 0; x < sw; ++x)
        if (const Material* m = reflective(tri[x])) ++samples, rays += rays_of(*m);
      row_samples[y + 1] = samples, row_rays[y + 1] = rays;
    }
  });
  for (size_t y = 0; y < size_t(sh); ++y) row_samples[y + 1] += row_samples[y], row_rays[y + 1] += row_rays[y];
  const size_t n = row_samples[size_t(sh)];
  frame.pixel.resize(n);
  frame.reflector.resize(n);
  frame.specular.resize(n);
  frame.gloss.resize(n);
  frame.first_ray.resize(n + 1);
  frame.first_ray[n] = row_rays[size_t(sh)];
  parallel_for(size_t(sh), 8, [&](size_t y0, size_t y1) {
    for (size_t y = y0; y < y1; ++y) {
      const uint32_t* tri = &g.triangle.at(0, int(y));
      size_t i = row_samples[y];
      uint32_t ray = row_rays[y];
      for (int x = 0; x < sw; ++x) {
        const Material* m = reflective(tri[x]);
        if (!m) continue;
        frame.pixel[i] = uint32_t(y) * uint32_t(sw) + uint32_t(x);
        frame.reflector[i] = scene.triangle_object[tri[x]];
        frame.specular[i] = m->specular;
        frame.gloss[i] = m->gloss;
        frame.first_ray[i] = ray;
        ray += rays_of(*m);
        ++i;
      }
    }
  });
  frame.position.resize(n);
  frame.normal.resize(n);
  frame.origin.resize(n);
  frame.direction.resize(frame.first_ray[n]);

  // The rays of render_reference's first bounce, from the same random streams.
  const float cell = options.lobe_seed_cell * frame.scene_diagonal;
  // The reference draws its area-light jitter (two numbers per stratum) before the lobe samples.
  const uint64_t light_draws = uint64_t(scene.area_lights.size()) * 2u *
                               uint64_t(options.area_light_samples) * uint64_t(options.area_light_samples);
  parallel_for(n, kSampleGrain, [&](size_t b, size_t e) {
    std::vector<vec2> lobe(size_t(options.glossy_rays));
    ShadedTriangle run;
    for (size_t i = b; i < e; ++i) {
      const int x = int(frame.pixel[i] % uint32_t(sw)), y = int(frame.pixel[i] / uint32_t(sw));
      const uint32_t t = g.triangle.at(x, y);
      const float u = g.barycentric.at(x, y, 0), v = g.barycentric.at(x, y, 1);
      const vec3 dir = glm::normalize(view.dir(x, y));
      if (t != run.triangle) run = ShadedTriangle(scene, t);
      const ShadedTriangle::Facing f = run.facing(u, v, -dir);
      frame.position[i] = run.point(u, v);
      frame.normal[i] = f.n;
      frame.origin[i] = frame.position[i] + epsilon * f.ng;
      const uint64_t out_pixel = uint64_t(y / k) * uint64_t(camera.width) + uint64_t(x / k);
      Pcg32 rng(cell > 0.0f ? surface_cell_seed(options.seed, frame.position[i], cell)
                            : derive_seed(options.seed, out_pixel, uint64_t((y % k) * k + (x % k))));
      if (light_draws > 0 && frame.specular[i] < 1.0f && surface_diffuse(scene, t, u, v) != vec3(0.0f))
        rng.advance(light_draws);
      const vec3 mirror = reflect(dir, f.n);
      const float half_angle = glossy_lobe_half_angle(frame.gloss[i]);
      const std::span<vec3> out(&frame.direction[frame.first_ray[i]], frame.first_ray[i + 1] - frame.first_ray[i]);
      if (half_angle > 0.0f) {
        stratified_samples_2d(lobe, rng);
        glossy_lobe_directions(mirror, f.ng, half_angle, lobe, out);
      } else {
        out[0] = glossy_lobe_direction(mirror, f.ng, 0.0f, vec2(0.0f));
      }
    }
  });
  return_gbuffer(std::move(g));
  frame.ms = watch.elapsed_ms();
  frame.rays_ms = frame.ms - frame.raster_ms - frame.shading_ms;
}

namespace {

// Rays traced per block whose hits are shaded together: enough lit hits to fill the lanes
// (a mirror sample has one ray), few enough to stay in cache.
constexpr uint32_t kBlockRays = 64;

// Samples sample_of(b) … sample_of(e − 1): each one's mean radiance over its rays, summed in
// ray order, into radiance[i]; with `hits`, each ray's closest hit (left as it is where the
// ray escapes). One kernel for every trace entry: the same bits.
template <bool kHits, class SampleOf>
void trace_samples(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame, size_t b, size_t e,
                   SampleOf sample_of, HitShading& shading, TracedReflections* hits, std::span<vec3> radiance) {
  for (size_t k0 = b; k0 < e;) {
    shading.clear();
    size_t k1 = k0;
    for (uint32_t traced = 0; k1 < e && traced < kBlockRays; ++k1) {
      const size_t i = sample_of(k1);
      for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r, ++traced) {
        const vec3 dir = frame.direction[r];
        const Hit hit = rays.intersect(Ray{frame.origin[i], dir, 0.0f, kInf});
        if (hit.valid()) {
          if constexpr (kHits) hits->hit_triangle[r] = hit.triangle, hits->hit_t[r] = hit.t;
          shading.add_hit(scene, hit.triangle, hit.u, hit.v, -dir);
        } else {
          shading.add_miss(environment_radiance(scene.environment, dir));
        }
      }
    }
    shading.finish();
    const vec3* color = shading.color.data();
    for (size_t k = k0; k < k1; ++k) {
      const size_t i = sample_of(k);
      const uint32_t count = frame.first_ray[i + 1] - frame.first_ray[i];
      vec3 sum(0.0f);
      for (uint32_t j = 0; j < count; ++j) sum += *color++;
      radiance[i] = sum / float(count);
    }
    k0 = k1;
  }
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
  const LightTable lights(scene, frame.area_light_samples);
  parallel_for(n, kSampleGrain, [&](size_t b, size_t e) {
    HitShading shading(lights);
    trace_samples<true>(scene, rays, frame, b, e, [](size_t k) { return k; }, shading, &out, out.radiance);
  });
  out.ms = watch.elapsed_ms();
}

void trace_reflection_samples(const Scene& scene, const RayScene& rays, const ReflectionFrame& frame,
                              std::span<const uint32_t> samples, std::span<vec3> radiance) {
  const LightTable lights(scene, frame.area_light_samples);
  parallel_for(samples.size(), kSampleGrain, [&](size_t b, size_t e) {
    HitShading shading(lights);
    trace_samples<false>(scene, rays, frame, b, e, [&](size_t k) { return size_t(samples[k]); }, shading, nullptr,
                         radiance);
  });
}

ImageF compose_reflections(const ReflectionFrame& frame, std::span<const vec3> reflected) {
  ImageF out;
  compose_reflections_into(frame, reflected, out);
  return out;
}

void compose_reflections_into(const ReflectionFrame& frame, std::span<const vec3> reflected, ImageF& out) {
  const int k = frame.supersample, w = frame.camera.width, h = frame.camera.height;
  const int sw = frame.sample_camera.width;
  if (out.width() != w || out.height() != h || out.channels() != 3) out = ImageF(w, h, 3);  // else all rewritten
  if (k == 1) {
    // The box filter over one sample: (0 + sample) / 1, i.e. the sample with −0 made +0.
    const float* base = frame.base.data().data();
    float* o = out.data().data();
    parallel_for(size_t(h), 16, [&](size_t y0, size_t y1) {
      for (size_t j = y0 * size_t(w) * 3; j < y1 * size_t(w) * 3; ++j) o[j] = 0.0f + base[j];
    });
    for (size_t i = 0; i < frame.sample_count(); ++i)
      for (int c = 0; c < 3; ++c) {
        const size_t j = 3 * size_t(frame.pixel[i]) + size_t(c);
        o[j] = 0.0f + (base[j] + frame.specular[i] * reflected[i][c]);
      }
    return;
  }
  ImageF samples = frame.base;
  for (size_t i = 0; i < frame.sample_count(); ++i) {
    const int x = int(frame.pixel[i] % uint32_t(sw)), y = int(frame.pixel[i] / uint32_t(sw));
    for (int c = 0; c < 3; ++c) samples.at(x, y, c) += frame.specular[i] * reflected[i][c];
  }
  parallel_for(size_t(h), 8, [&](size_t y0, size_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          float sum = 0.0f;
          for (int j = 0; j < k; ++j)
            for (int i = 0; i < k; ++i) sum += samples.at(x * k + i, y * k + j, c);
          out.at(x, y, c) = sum / float(k * k);
        }
  });
}

ImageU8 reflective_pixel_mask(const ReflectionFrame& frame) {
  ImageU8 mask(frame.camera.width, frame.camera.height, 1, 0);
  const int sw = frame.sample_camera.width, k = frame.supersample;
  for (uint32_t px : frame.pixel) mask.at(int(px % uint32_t(sw)) / k, int(px / uint32_t(sw)) / k) = 1;
  return mask;
}

}  // namespace proxima