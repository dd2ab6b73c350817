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
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// The eight-lane shading path: GCC optimized builds only, as the best match's AVX-512 path
// (temporal_best_match.cpp) — unoptimized, the lane ops would not be inlined into the avx
// code and would pass __m256 across targets; clang rejects the default-target template.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__OPTIMIZE__)
#include <immintrin.h>
#define PROXIMA_SHADE_AVX 1
#pragma GCC diagnostic ignored "-Wpsabi"
#else
#define PROXIMA_SHADE_AVX 0
#endif

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

struct Facing {
  vec3 ng, n;
};

// What shading reads of a triangle, its vertices loaded once (a run of pixels or samples
// often shows one triangle): shading_normal and triangle_point from the loaded corners by
// the same expressions (the same bits), and the two-sided surface as seen from a viewer (as
// trace/'s surface_point_seen).
struct ShadedTriangle {
  ShadedTriangle() = default;
  ShadedTriangle(const Scene& scene, uint32_t t)
      : triangle(t), ng(triangle_normal(scene, t)), material(&scene.materials[scene.triangle_material[t]]) {
    const uvec3& i = scene.triangles[t];
    n0 = scene.normals[i.x], n1 = scene.normals[i.y], n2 = scene.normals[i.z];
    p0 = scene.positions[i.x], p1 = scene.positions[i.y], p2 = scene.positions[i.z];
  }
  vec3 shading_normal(float u, float v) const {
    const vec3 n = barycentric(n0, n1, n2, u, v);
    const float len = glm::length(n);
    return len > 0.0f ? n / len : ng;
  }
  vec3 point(float u, float v) const { return barycentric(p0, p1, p2, u, v); }
  Facing facing(float u, float v, vec3 toward_viewer) const {
    Facing f;
    f.ng = ng;
    if (glm::dot(f.ng, toward_viewer) < 0.0f) f.ng = -f.ng;
    f.n = shading_normal(u, v);
    if (glm::dot(f.n, f.ng) < 0.0f) f.n = -f.n;
    return f;
  }

  uint32_t triangle = kNoTriangle;
  vec3 ng{0.0f};  // triangle_normal: the geometric normal, not yet facing the viewer
  const Material* material = nullptr;
  vec3 n0{0.0f}, n1{0.0f}, n2{0.0f}, p0{0.0f}, p1{0.0f}, p2{0.0f};
};

}  // namespace

vec3 shade_reflected_point(const Scene& scene, uint32_t triangle, float u, float v, vec3 toward_viewer,
                           int area_light_samples) {
  const ShadedTriangle tri(scene, triangle);
  const Material& m = *tri.material;
  const Facing f = tri.facing(u, v, toward_viewer);
  const vec3 p = tri.point(u, v);
  ShadingTerms terms;
  terms.emission = m.emission;
  terms.ambient = scene.ambient;
  terms.albedo = surface_diffuse(scene, triangle, u, v);
  terms.specular = m.specular;
  if (m.specular < 1.0f && terms.albedo != vec3(0.0f)) {
    for (const PointLight& light : scene.point_lights) terms.direct_irradiance += point_light_irradiance(light, p, f.n);
    const int n = area_light_samples;
    for (const AreaLight& light : scene.area_lights) {
      const vec3 normal = light.normal();
      const float area = light.area();
      vec3 sum(0.0f);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          vec2 ab = stratum_sample(i, j, n, 0.5f, 0.5f);
          sum += area_light_sample_irradiance(light, normal, area, light.point(ab.x, ab.y), p, f.n);
        }
      terms.direct_irradiance += sum / float(n * n);
    }
  }
  return combine_shading(terms);
}

namespace {

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

// The lights as shade_reflected_point evaluates them, with what it recomputes per sample
// (each area light's normal and area, its n×n stratum centres) computed once per frame by
// the same expressions: the same values. Points are stored per coordinate for the lanes.
struct LightTable {
  struct Area {
    vec3 normal, radiance;
    float area = 0.0f;
    std::vector<float> x, y, z;  // the n×n stratum centres in shade_reflected_point's order
  };
  std::vector<PointLight> points;
  std::vector<Area> areas;
  float samples = 1.0f;  // float(n·n)

  LightTable(const Scene& scene, int n) : points(scene.point_lights), samples(float(n * n)) {
    for (const AreaLight& light : scene.area_lights) {
      Area a;
      a.normal = light.normal();
      a.radiance = light.radiance;
      a.area = light.area();
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const vec2 ab = stratum_sample(i, j, n, 0.5f, 0.5f);
          const vec3 q = light.point(ab.x, ab.y);
          a.x.push_back(q.x);
          a.y.push_back(q.y);
          a.z.push_back(q.z);
        }
      areas.push_back(std::move(a));
    }
  }
};

// Lit points of one row, per coordinate (padded to whole lane groups), and their unshadowed
// direct irradiance.
struct LitPoints {
  std::vector<float> px, py, pz, nx, ny, nz, ex, ey, ez;
  size_t count = 0;

  void clear() { count = 0; }
  void add(vec3 p, vec3 n) {
    if (px.size() <= count) {
      for (auto* v : {&px, &py, &pz, &nx, &ny, &nz, &ex, &ey, &ez}) v->resize(std::max<size_t>(64, 2 * count), 0.0f);
    }
    px[count] = p.x, py[count] = p.y, pz[count] = p.z;
    nx[count] = n.x, ny[count] = n.y, nz[count] = n.z;
    ++count;
  }
};

#if defined(__SSE2__)
#define PROXIMA_LANE_OP static inline __attribute__((always_inline))
struct Lanes4 {
  using V = __m128;
  static constexpr size_t kWidth = 4;
  PROXIMA_LANE_OP V zero() { return _mm_setzero_ps(); }
  PROXIMA_LANE_OP V set1(float v) { return _mm_set1_ps(v); }
  PROXIMA_LANE_OP V load(const float* p) { return _mm_loadu_ps(p); }
  PROXIMA_LANE_OP void store(float* p, V v) { _mm_storeu_ps(p, v); }
  PROXIMA_LANE_OP V add(V a, V b) { return _mm_add_ps(a, b); }
  PROXIMA_LANE_OP V sub(V a, V b) { return _mm_sub_ps(a, b); }
  PROXIMA_LANE_OP V mul(V a, V b) { return _mm_mul_ps(a, b); }
  PROXIMA_LANE_OP V div(V a, V b) { return _mm_div_ps(a, b); }
  PROXIMA_LANE_OP V sqrt(V a) { return _mm_sqrt_ps(a); }
  PROXIMA_LANE_OP V neg(V a) { return _mm_xor_ps(a, _mm_set1_ps(-0.0f)); }
  PROXIMA_LANE_OP V keep(V mask, V a) { return _mm_and_ps(mask, a); }
  PROXIMA_LANE_OP V both(V a, V b) { return _mm_and_ps(a, b); }
  PROXIMA_LANE_OP V gt0(V a) { return _mm_cmplt_ps(_mm_setzero_ps(), a); }     // 0 < a (NaN: false)
  PROXIMA_LANE_OP V dot(V ax, V ay, V az, V bx, V by, V bz) { return add(add(mul(ax, bx), mul(ay, by)), mul(az, bz)); }
  PROXIMA_LANE_OP V not_le0(V a) { return _mm_cmpnle_ps(a, _mm_setzero_ps()); }  // !(a <= 0) (NaN: true)
};

// The direct irradiance of shade_reflected_point for L::kWidth points at once: each lane
// runs point_light_irradiance's and area_light_sample_irradiance's IEEE single operations
// in their order (dot = (x·x' + y·y') + z·z', max(0, c) as 0 < c ? c : +0, a returned 0
// added as +0; no fused multiply-add on these targets, so nothing is contracted): per lane
// the scalar code's bits.
template <class L>
inline __attribute__((always_inline)) void direct_irradiance_lanes(const LightTable& lights, LitPoints& lit) {
  using V = typename L::V;
  for (size_t i = 0; i < lit.count; i += L::kWidth) {
    const V px = L::load(&lit.px[i]), py = L::load(&lit.py[i]), pz = L::load(&lit.pz[i]);
    const V nx = L::load(&lit.nx[i]), ny = L::load(&lit.ny[i]), nz = L::load(&lit.nz[i]);
    V ex = L::zero(), ey = L::zero(), ez = L::zero();
    for (const PointLight& light : lights.points) {
      const V tx = L::sub(L::set1(light.position.x), px);
      const V ty = L::sub(L::set1(light.position.y), py);
      const V tz = L::sub(L::set1(light.position.z), pz);
      const V r2 = L::dot(tx, ty, tz, tx, ty, tz);
      const V c = L::div(L::dot(nx, ny, nz, tx, ty, tz), L::sqrt(r2));
      const V q = L::div(L::keep(L::gt0(c), c), r2);  // max(0, c) / r²
      const V keep = L::not_le0(r2);                   // r² <= 0 gives 0
      ex = L::add(ex, L::keep(keep, L::mul(L::set1(light.intensity.x), q)));
      ey = L::add(ey, L::keep(keep, L::mul(L::set1(light.intensity.y), q)));
      ez = L::add(ez, L::keep(keep, L::mul(L::set1(light.intensity.z), q)));
    }
    for (const LightTable::Area& a : lights.areas) {
      const V lnx = L::set1(a.normal.x), lny = L::set1(a.normal.y), lnz = L::set1(a.normal.z);
      const V area = L::set1(a.area);
      const V rx = L::set1(a.radiance.x), ry = L::set1(a.radiance.y), rz = L::set1(a.radiance.z);
      V sx = L::zero(), sy = L::zero(), sz = L::zero();
      for (size_t k = 0; k < a.x.size(); ++k) {
        const V tx = L::sub(L::set1(a.x[k]), px);
        const V ty = L::sub(L::set1(a.y[k]), py);
        const V tz = L::sub(L::set1(a.z[k]), pz);
        const V r2 = L::dot(tx, ty, tz, tx, ty, tz);
        const V r = L::sqrt(r2);
        const V cs = L::div(L::dot(nx, ny, nz, tx, ty, tz), r);
        const V cl = L::div(L::neg(L::dot(lnx, lny, lnz, tx, ty, tz)), r);
        const V f = L::mul(L::div(L::mul(cs, cl), r2), area);
        // 0 where r² <= 0, cos_surface <= 0 or cos_light <= 0 (NaN passes, as in the scalar test)
        const V keep = L::both(L::not_le0(r2), L::both(L::not_le0(cs), L::not_le0(cl)));
        sx = L::add(sx, L::keep(keep, L::mul(rx, f)));
        sy = L::add(sy, L::keep(keep, L::mul(ry, f)));
        sz = L::add(sz, L::keep(keep, L::mul(rz, f)));
      }
      const V m = L::set1(lights.samples);
      ex = L::add(ex, L::div(sx, m));
      ey = L::add(ey, L::div(sy, m));
      ez = L::add(ez, L::div(sz, m));
    }
    L::store(&lit.ex[i], ex);
    L::store(&lit.ey[i], ey);
    L::store(&lit.ez[i], ez);
  }
}

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
// Eight lanes where the CPU has AVX (runtime dispatch). target("avx") brings no fused
// multiply-add, so the operations stay separate: the same bits as four lanes.
#define PROXIMA_AVX_OP static __attribute__((target("avx"))) inline
struct Lanes8 {
  using V = __m256;
  static constexpr size_t kWidth = 8;
  PROXIMA_AVX_OP V zero() { return _mm256_setzero_ps(); }
  PROXIMA_AVX_OP V set1(float v) { return _mm256_set1_ps(v); }
  PROXIMA_AVX_OP V load(const float* p) { return _mm256_loadu_ps(p); }
  PROXIMA_AVX_OP void store(float* p, V v) { _mm256_storeu_ps(p, v); }
  PROXIMA_AVX_OP V add(V a, V b) { return _mm256_add_ps(a, b); }
  PROXIMA_AVX_OP V sub(V a, V b) { return _mm256_sub_ps(a, b); }
  PROXIMA_AVX_OP V mul(V a, V b) { return _mm256_mul_ps(a, b); }
  PROXIMA_AVX_OP V div(V a, V b) { return _mm256_div_ps(a, b); }
  PROXIMA_AVX_OP V sqrt(V a) { return _mm256_sqrt_ps(a); }
  PROXIMA_AVX_OP V neg(V a) { return _mm256_xor_ps(a, _mm256_set1_ps(-0.0f)); }
  PROXIMA_AVX_OP V keep(V mask, V a) { return _mm256_and_ps(mask, a); }
  PROXIMA_AVX_OP V both(V a, V b) { return _mm256_and_ps(a, b); }
  PROXIMA_AVX_OP V gt0(V a) { return _mm256_cmp_ps(_mm256_setzero_ps(), a, _CMP_LT_OS); }
  PROXIMA_AVX_OP V dot(V ax, V ay, V az, V bx, V by, V bz) { return add(add(mul(ax, bx), mul(ay, by)), mul(az, bz)); }
  PROXIMA_AVX_OP V not_le0(V a) { return _mm256_cmp_ps(a, _mm256_setzero_ps(), _CMP_NLE_US); }
};

__attribute__((target("avx"), flatten)) void direct_irradiance_avx(const LightTable& lights, LitPoints& lit) {
  direct_irradiance_lanes<Lanes8>(lights, lit);
}

__attribute__((target("avx"), flatten)) void view_dirs_avx(const ViewRays& view, int y, RowDirs& out) {
  view_dirs_lanes<Lanes8>(view, y, out);
}

bool has_avx() {
  static const bool yes = __builtin_cpu_supports("avx");
  return yes;
}
#endif

void direct_irradiance(const LightTable& lights, LitPoints& lit) {
#if PROXIMA_SHADE_AVX
  if (has_avx()) return direct_irradiance_avx(lights, lit);
#endif
  direct_irradiance_lanes<Lanes4>(lights, lit);
}

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

void direct_irradiance(const LightTable& lights, LitPoints& lit) {
  for (size_t i = 0; i < lit.count; ++i) {
    const vec3 p(lit.px[i], lit.py[i], lit.pz[i]), n(lit.nx[i], lit.ny[i], lit.nz[i]);
    vec3 e(0.0f);
    for (const PointLight& light : lights.points) e += point_light_irradiance(light, p, n);
    for (const LightTable::Area& a : lights.areas) {
      vec3 sum(0.0f);
      for (size_t k = 0; k < a.x.size(); ++k) {  // area_light_sample_irradiance with the table's values
        const vec3 to_light = vec3(a.x[k], a.y[k], a.z[k]) - p;
        const float r2 = glm::dot(to_light, to_light);
        const float r = std::sqrt(r2);
        const float cs = glm::dot(n, to_light) / r, cl = -glm::dot(a.normal, to_light) / r;
        const bool keep = !(r2 <= 0.0f) && !(cs <= 0.0f) && !(cl <= 0.0f);
        sum += keep ? a.radiance * (cs * cl / r2 * a.area) : vec3(0.0f);
      }
      e += sum / lights.samples;
    }
    lit.ex[i] = e.x, lit.ey[i] = e.y, lit.ez[i] = e.z;
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
// view ray — the point lights and area-light stratum centres four pixels at a time.
void shade_base_row(const Scene& scene, const RasterImages& g, const ViewRays& view, const LightTable& lights, int y,
                    RowDirs& dirs, LitPoints& lit, std::vector<ShadingTerms>& terms, std::vector<uint32_t>& lit_x,
                    ImageF& base) {
  const int sw = g.triangle.width();
  const uint32_t* tri = &g.triangle.at(0, y);
  const float* bary = &g.barycentric.at(0, y);
  float* out = &base.at(0, y);
  lit.clear();
  lit_x.clear();
  terms.clear();
  ShadedTriangle run;
  view_dirs(view, y, dirs);
  // The lanes must give dir()'s bits (a build that fuses multiply-adds in one and not the
  // other would not): one pixel of each row, a different column per row, is checked.
  const int cx = y % sw;
  const vec3 check = view.dir(cx, y);
  if (check != vec3(dirs.x[size_t(cx)], dirs.y[size_t(cx)], dirs.z[size_t(cx)]))
    throw std::logic_error("reflection frame: the lanes' view direction differs from the scalar one");
  for (int x = 0; x < sw; ++x) {
    const uint32_t t = tri[x];
    const vec3 dir(dirs.x[size_t(x)], dirs.y[size_t(x)], dirs.z[size_t(x)]);
    if (t == kNoTriangle) {
      const vec3 c = environment_radiance(scene.environment, dir);
      out[3 * x] = c.x, out[3 * x + 1] = c.y, out[3 * x + 2] = c.z;
      continue;
    }
    const float u = bary[2 * x], v = bary[2 * x + 1];
    if (t != run.triangle) run = ShadedTriangle(scene, t);
    // facing(): the two-sided surface seen from −dir.
    const vec3 toward = -dir;
    vec3 ng = run.ng;
    if (glm::dot(ng, toward) < 0.0f) ng = -ng;
    vec3 n = run.shading_normal(u, v);
    if (glm::dot(n, ng) < 0.0f) n = -n;
    const Material& m = *run.material;
    ShadingTerms st;
    st.emission = m.emission;
    st.ambient = scene.ambient;
    st.albedo = surface_diffuse(scene, t, u, v);
    st.specular = m.specular;
    if (m.specular < 1.0f && st.albedo != vec3(0.0f)) {
      lit.add(run.point(u, v), n);
      lit_x.push_back(uint32_t(x));
      terms.push_back(st);
      continue;
    }
    const vec3 c = combine_shading(st);
    out[3 * x] = c.x, out[3 * x + 1] = c.y, out[3 * x + 2] = c.z;
  }
  direct_irradiance(lights, lit);
  for (size_t i = 0; i < lit_x.size(); ++i) {
    terms[i].direct_irradiance = vec3(lit.ex[i], lit.ey[i], lit.ez[i]);
    const vec3 c = combine_shading(terms[i]);
    const size_t x = lit_x[i];
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
    LitPoints lit;
    std::vector<ShadingTerms> terms;
    std::vector<uint32_t> lit_x;
    for (int y = int(y0); y < int(y1); ++y)
      shade_base_row(scene, g, view, lights, y, dirs, lit, terms, lit_x, frame.base);
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
      const Facing f = run.facing(u, v, -dir);
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