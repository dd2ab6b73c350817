// The reference renderer: Whitted-style ray tracing of the shared shading model
// (docs/shading.md, scene/shading.h) with Embree. Every approximation is judged against it.
//
// Per (sub-)sample: primary ray → closest hit → emission + ambient + Lambert direct light
// (shadow ray per point light, n×n stratified shadow rays per area light) + s × reflected
// radiance. Reflections recurse up to max_bounces; the glossy lobe (glossy_rays stratified
// rays) is sampled only at the first bounce, deeper bounces follow the mirror ray alone.
// Escaping rays read environment_radiance().
#include "proxima/trace/reference_renderer.h"

#include <algorithm>
#include <string>
#include <vector>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/scene/shading.h"
#include "proxima/trace/direct_light.h"

namespace proxima {
namespace {

constexpr int kTileSize = 16;

// Primary ray through continuous pixel coordinates, clipped to the camera's [near, far]
// slab like a rasterizer's depth range.
Ray primary_ray(const Camera& camera, vec3 forward, vec2 pixel) {
  Ray ray = ray_through(camera, pixel);
  float cos_axis = glm::dot(ray.dir, forward) / glm::length(ray.dir);
  ray.tmin = camera.near / cos_axis;
  ray.tmax = camera.far / cos_axis;
  return ray;
}

class Tracer {
 public:
  Tracer(const Scene& scene, const RayScene& rays, const ReferenceOptions& options)
      : scene_(scene), rays_(rays), options_(options), light_(scene, rays, options.area_light_samples) {}

  // Radiance arriving along `ray` (towards its origin). `bounce` = reflections taken so far.
  // `lobe` is scratch for options.glossy_rays samples; only bounce 0 fills it, so the
  // recursion can pass it on.
  vec3 radiance(const Ray& ray, int bounce, Pcg32& rng, std::span<vec2> lobe) const {
    Hit hit = rays_.intersect(ray);
    if (!hit.valid()) return environment_radiance(scene_.environment, ray.dir);
    SurfacePoint sp = surface_point_seen(scene_, hit.triangle, hit.u, hit.v, ray.dir);
    ShadingTerms terms = light_.local_terms(sp, rng);
    const float s = terms.specular;
    if (s > 0.0f && bounce < options_.max_bounces) {
      vec3 mirror = reflect(glm::normalize(ray.dir), sp.n);
      Ray reflected{light_.offset_origin(sp), mirror, 0.0f, kInf};
      float half_angle = glossy_lobe_half_angle(scene_.materials[scene_.triangle_material[hit.triangle]].gloss);
      if (bounce == 0 && half_angle > 0.0f) {
        stratified_samples_2d(lobe, rng);
        vec3 sum(0.0f);
        for (vec2 u : lobe) {
          reflected.dir = glossy_lobe_direction(mirror, sp.ng, half_angle, u);
          sum += radiance(reflected, bounce + 1, rng, lobe);
        }
        terms.reflected = sum / float(lobe.size());
      } else {
        // A shading normal may tilt the mirror ray under the surface: fold it back up.
        reflected.dir = glossy_lobe_direction(mirror, sp.ng, 0.0f, vec2(0.0f));
        terms.reflected = radiance(reflected, bounce + 1, rng, lobe);
      }
    }
    return combine_shading(terms);
  }

 private:
  const Scene& scene_;
  const RayScene& rays_;
  const ReferenceOptions& options_;
  DirectLight light_;
};

void validate_options(const ReferenceOptions& o) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) fail_input("reference renderer: " + what);
  };
  require(o.supersample >= 1 && o.supersample <= 64, "supersample must be in [1, 64]");
  require(o.area_light_samples >= 1 && o.area_light_samples <= 256, "area light samples must be in [1, 256]");
  require(o.glossy_rays >= 1 && o.glossy_rays <= 4096, "glossy rays must be in [1, 4096]");
  require(o.max_bounces >= 0 && o.max_bounces <= 64, "max bounces must be in [0, 64]");
  require(o.row_begin >= 0 && (o.row_end == -1 || o.row_end >= o.row_begin), "rows must satisfy 0 ≤ begin ≤ end");
}

}  // namespace

ItemBuffer trace_item_buffer(const Scene& scene, const RayScene& rays, const Camera& camera) {
  validate_camera(camera, "item buffer camera");
  int w = camera.width;
  int h = camera.height;
  ItemBuffer out{ImageU32(w, h, 1, kNoTriangle), ImageF(w, h, 1, kInf), ImageF(w, h, 3, 0.0f),
                 ImageF(w, h, 3, 0.0f), ImageF(w, h, 2, 0.0f)};
  vec3 forward = camera_forward(camera);
  parallel_for_tiles(w, h, kTileSize, [&](const Tile& tile) {
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        Ray ray = primary_ray(camera, forward, vec2(float(x) + 0.5f, float(y) + 0.5f));
        Hit hit = rays.intersect(ray);
        if (!hit.valid()) continue;
        SurfacePoint sp = surface_point_seen(scene, hit.triangle, hit.u, hit.v, ray.dir);
        out.triangle.at(x, y) = hit.triangle;
        out.depth.at(x, y) = hit.t * glm::dot(ray.dir, forward);
        for (int c = 0; c < 3; ++c) {
          out.normal.at(x, y, c) = sp.n[c];
          out.position.at(x, y, c) = sp.p[c];
        }
        out.barycentric.at(x, y, 0) = hit.u;
        out.barycentric.at(x, y, 1) = hit.v;
      }
  });
  return out;
}

ImageF render_reference(const Scene& scene, const RayScene& rays, const Camera& camera,
                        const ReferenceOptions& options) {
  validate_camera(camera, "reference camera");
  validate_options(options);
  int w = camera.width;
  int h = camera.height;
  int k = options.supersample;
  ImageF out(w, h, 3, 0.0f);
  vec3 forward = camera_forward(camera);
  Tracer tracer(scene, rays, options);
  const int row_end = options.row_end < 0 ? h : std::min(options.row_end, h);
  parallel_for_tiles(w, h, kTileSize, [&](const Tile& tile) {
    std::vector<vec2> lobe(size_t(options.glossy_rays));
    for (int y = std::max(tile.y0, options.row_begin); y < std::min(tile.y1, row_end); ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        uint64_t pixel_index = uint64_t(y) * uint64_t(w) + uint64_t(x);
        vec3 sum(0.0f);
        // k×k sub-pixel samples at the centers of a regular grid (the pixel center for
        // k = 1), each with its own random stream; summed in a fixed order.
        for (int sj = 0; sj < k; ++sj)
          for (int si = 0; si < k; ++si) {
            Pcg32 rng(derive_seed(options.seed, pixel_index, uint64_t(sj * k + si)));
            vec2 pixel{float(x) + (float(si) + 0.5f) / float(k), float(y) + (float(sj) + 0.5f) / float(k)};
            sum += tracer.radiance(primary_ray(camera, forward, pixel), 0, rng, lobe);
          }
        vec3 color = sum / float(k * k);
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = color[c];
      }
  });
  return out;
}

}  // namespace proxima
