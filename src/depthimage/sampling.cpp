// Non-redundant rendering of depth-image sets.
// Paper: Xie Naiwen, PhD thesis (Beihang), "Approximate representations of complex scenes
// and rendering", ch. 2 (../shared/papers/004_d1af2812aec5f9c7.txt, lines 537–800):
// Algorithm 1 (NRR), Algorithm 2 (visibility redundancy), Algorithm 3 (pixel redundancy).
//
// Symbol ↔ variable:
//   S                    scene
//   PPC_i, V_i           cameras[i], cameras[i].position
//   I_i                  images[i] (DepthImage)
//   s (sample)           a Fragment: pixel (x, y), depth, triangle t
//   a (s unprojected)    unproject(from, pixel center, depth)
//   b = V_j a ∩ S        first front-facing hit of the segment V_j → a (up to a − ε)
//   r, t_r               reprojected pixel in I_j, against.triangle at r
//   "z-buffer test"      the rasterizer's (depth, id) depth test; the redundancy loop over
//                        j < i is the fragment test (NonRedundantTest)
#include "proxima/depthimage/sampling.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cassert>
#include <cmath>
#include <numeric>
#include <utility>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/raster/depth_peeling.h"

namespace proxima {

namespace {
constexpr int kMaxBackFaces = 8;  // back-facing hits the visibility ray walks past
}  // namespace

const char* redundancy_name(Redundancy r) { return r == Redundancy::Pixel ? "pixel" : "visibility"; }

Redundancy parse_redundancy(const std::string& name, const char* flag) {
  for (Redundancy r : {Redundancy::Pixel, Redundancy::Visibility})
    if (name == redundancy_name(r)) return r;
  fail_input(std::string(flag) + ": unknown redundancy '" + name + "' (pixel, visibility)");
}

RedundancyTest::RedundancyTest(Redundancy kind, const Scene& scene, const RayScene* rays, const Camera& from,
                               const DepthImage& against, float epsilon)
    : kind_(kind), scene_(&scene), rays_(rays), from_(&from), against_(&against),
      reproject_(from, against.camera),
      // Only the visibility test uses ε; the bounds are a pass over every vertex.
      epsilon_(kind == Redundancy::Visibility ? epsilon * scene_bounds(scene).diagonal() : 0.0f) {
  assert(kind != Redundancy::Visibility || rays != nullptr);
}

bool RedundancyTest::operator()(int x, int y, float depth, uint32_t triangle) const {
  const Camera& to = against_->camera;
  vec2 r;
  float to_depth;
  if (!reproject_.map(x, y, depth, r, to_depth)) return false;
  int rx, ry;
  if (!pixel_in(to, r, rx, ry)) return false;
  if (kind_ == Redundancy::Pixel) return against_->triangle.at(rx, ry) == triangle;

  // Visibility: in V_j's frustum, facing V_j, and the segment V_j → a unoccluded.
  if (to_depth < to.near || to_depth > to.far) return false;
  const vec3 a = unproject(*from_, vec2(float(x) + 0.5f, float(y) + 0.5f), depth);
  const vec3 d = a - to.position;
  if (glm::dot(triangle_normal(*scene_, triangle), d) >= 0.0f) return false;
  const float length = glm::length(d);
  if (length <= epsilon_) return true;
  Ray ray;
  ray.origin = to.position;
  ray.dir = d;
  ray.tmin = 0.0f;
  ray.tmax = 1.0f - epsilon_ / length;  // b closer than a − ε means occluded
  // Back faces do not occlude: the images cull them, and a closed or double-sided
  // surface always has a front face in front of its back face — except where a thin
  // double-sided sliver (a blade tip) is narrower than a pixel and only one of its two
  // sides covers the pixel center. So walk past back-facing hits.
  for (int k = 0; k < kMaxBackFaces; ++k) {
    const Hit hit = rays_->intersect(ray);
    if (!hit.valid()) return true;
    if (glm::dot(triangle_normal(*scene_, hit.triangle), d) < 0.0f) return false;
    ray.tmin = std::nextafter(hit.t, kInf);
  }
  return false;  // more back faces than we walk past: call it occluded
}

namespace {

// x and depth of fragments k … k+3 of a run of n (past n: copies of the last, ignored).
inline void gather4(const Fragment* fragments, int k, int n, int x[4], float d[4]) {
  for (int l = 0; l < 4; ++l) {
    const Fragment& f = fragments[std::min(k + l, n - 1)];
    x[l] = f.x;
    d[l] = f.depth;
  }
}

}  // namespace

uint64_t RedundancyTest::redundant_run(const Fragment* fragments, int n, uint64_t candidates) const {
  assert(n >= 0 && n <= 64);
  uint64_t redundant = 0;
  if (kind_ != Redundancy::Pixel) {
    for (int k = 0; k < n; ++k) {
      const Fragment& f = fragments[k];
      if (((candidates >> k) & 1u) && (*this)(f.x, f.y, f.depth, f.triangle)) redundant |= uint64_t(1) << k;
    }
    return redundant;
  }
  const uint32_t triangle = fragments[0].triangle;  // one triangle's run
  for (int k = 0; k < n; k += 4) {
    const unsigned lanes = unsigned(candidates >> k) & 0xFu;
    if (lanes == 0) continue;
    int x[4];
    float d[4];
    gather4(fragments, k, n, x, d);
    redundant |= uint64_t(redundant4(x, fragments[k].y, d, triangle, lanes)) << k;
  }
  return redundant;
}

std::vector<DepthImage> sample_conventional(const Scene& scene, std::span<const Camera> cameras, bool shade) {
  std::vector<DepthImage> images;
  for (const Camera& c : cameras) images.push_back(render_depth_image(scene, c, shade));
  return images;
}

std::vector<DepthImage> sample_peeling(const Scene& scene, const Camera& camera, int layers, bool shade) {
  DepthPeelOptions options;
  options.max_layers = layers;
  options.raster = depth_image_raster_options(shade);
  std::vector<RasterImages> peeled = depth_peel(scene, camera, options);
  std::vector<DepthImage> images;
  for (RasterImages& layer : peeled) images.push_back(to_depth_image(camera, std::move(layer)));
  // Empty layers past the last one peeled, so the set always has `layers` images.
  while (images.size() < size_t(layers)) {
    DepthImage empty;
    empty.camera = camera;
    empty.depth = ImageF(camera.width, camera.height, 1, kInf);
    empty.triangle = ImageU32(camera.width, camera.height, 1, kNoTriangle);
    if (shade) {
      empty.normal = ImageF(camera.width, camera.height, 3, 0.0f);
      empty.color = ImageF(camera.width, camera.height, 3, 0.0f);
    }
    images.push_back(std::move(empty));
  }
  return images;
}

namespace {

// Algorithm 1's inner loop as the rasterizer's fragment test: keep a fragment only if it
// is redundant with none of the earlier images. The loop over earlier images is kept out
// of line so it does not bloat the rasterizer's coverage loop (measured ~10 % faster on
// nest, on a loaded machine).
// Pixel redundancy with I_j needs I_j to hold the fragment's triangle somewhere, so with
// `held` (bit min(j, 7) of held[t] set iff image j holds triangle t) a fragment is
// reprojected only into the earlier images that hold its triangle, and kept at once when
// none does: the same answer, cheaper.
struct NonRedundantTest {
  std::span<const RedundancyTest> earlier;
  const uint8_t* held = nullptr;  // pixel redundancy only; null: test every image

  bool operator()(const Fragment& f) const {
    if (!held) return !redundant(f, 0xFFu);
    const uint8_t mask = held[f.triangle];
    return mask == 0 || !redundant(f, mask);
  }
  [[gnu::noinline]] bool redundant(const Fragment& f, uint8_t mask) const {
    for (size_t j = 0; j < earlier.size(); ++j)
      if (((mask >> std::min<size_t>(j, 7)) & 1u) && earlier[j](f.x, f.y, f.depth, f.triangle)) return true;
    return false;
  }
  // A triangle that no earlier image holds cannot be pixel-redundant: the rasterizer
  // then skips the test for its fragments (no run arrays).
  bool keeps_all(uint32_t triangle) const { return held && held[triangle] == 0; }
  // The rasterizer fetches held[] ahead of keeps_all (a scattered byte per triangle).
  void prefetch(uint32_t triangle) const {
    if (held) __builtin_prefetch(held + triangle);
  }
  // The rasterizer's run form (one triangle, one row): the same answers, with the
  // presence mask read once per run and four fragments at a time, each four tested
  // against every earlier image holding the triangle before the next four (pixel
  // redundancy; the x, depth gather and the run stay in registers / L1).
  uint64_t keep_run(const Fragment* f, int n) const {
    uint64_t keep = n == 64 ? ~uint64_t(0) : (uint64_t(1) << n) - 1;
    if (!held) {
      for (size_t j = 0; j < earlier.size() && keep != 0; ++j) keep &= ~earlier[j].redundant_run(f, n, keep);
      return keep;
    }
    const uint8_t mask = held[f[0].triangle];
    if (mask == 0) return keep;
    const uint32_t triangle = f[0].triangle;
    const int y = f[0].y;
    for (int k = 0; k < n; k += 4) {
      int x[4];
      float d[4];
      gather4(f, k, n, x, d);
      unsigned lanes = unsigned(keep >> k) & 0xFu;
      for (size_t j = 0; j < earlier.size() && lanes != 0; ++j)
        if ((mask >> std::min<size_t>(j, 7)) & 1u) lanes &= ~earlier[j].redundant4(x, y, d, triangle, lanes);
      keep = (keep & ~(uint64_t(0xFu) << k)) | (uint64_t(lanes) << k);
    }
    return keep;
  }
};

// A float's bits as an unsigned key in the float's order (−0 sorts before +0).
uint32_t ordered_bits(float f) {
  const uint32_t b = std::bit_cast<uint32_t>(f);
  return (b & 0x80000000u) ? ~b : b | 0x80000000u;
}

// The front-to-back draw order sorts clusters of consecutive triangles, not triangles:
// consecutive triangles are one mesh strip, blade, box or leaf in practice (spatially
// compact). The sort is 16× shorter and the rasterizer's setup reads the triangles and
// their vertices in runs instead of scattered; early z is a little worse (1024², 3 views:
// 0–3 % more fragments tested on city and tree, 10–17 % on grass and nest), and the
// measured time no worse than with the per-triangle sort (docs/journal/sampling.md).
constexpr size_t kClusterTriangles = 16;

// Centroid of each cluster's triangle centroids.
std::vector<vec3> cluster_centers(const Scene& scene) {
  const size_t n = scene.triangles.size();
  std::vector<vec3> centers((n + kClusterTriangles - 1) / kClusterTriangles);
  parallel_for(centers.size(), 1024, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) {
      const size_t t0 = c * kClusterTriangles, t1 = std::min(n, t0 + kClusterTriangles);
      vec3 sum(0.0f);
      for (size_t t = t0; t < t1; ++t) {
        const uvec3 tri = scene.triangles[t];
        sum += scene.positions[tri.x] + scene.positions[tri.y] + scene.positions[tri.z];
      }
      centers[c] = sum / float(3 * (t1 - t0));
    }
  });
  return centers;
}

// Triangle ids, clusters sorted front to back by the view depth of their centers (ties
// by cluster), each cluster's triangles in scene order. `order` is reused.
void front_to_back(const Scene& scene, std::span<const vec3> centers, const Camera& camera,
                   std::vector<uint32_t>& order) {
  const vec3 eye = camera.position, forward = camera_forward(camera);
  std::vector<uint64_t> keys(centers.size());
  for (size_t c = 0; c < keys.size(); ++c)
    keys[c] = (uint64_t(ordered_bits(glm::dot(centers[c] - eye, forward))) << 32) | uint64_t(c);
  std::sort(keys.begin(), keys.end());
  const size_t n = scene.triangles.size();
  order.resize(n);
  size_t k = 0;
  for (uint64_t key : keys) {
    const size_t t0 = size_t(uint32_t(key)) * kClusterTriangles, t1 = std::min(n, t0 + kClusterTriangles);
    for (size_t t = t0; t < t1; ++t) order[k++] = uint32_t(t);
  }
}

// Sets `bit` in held[t] for every triangle t the image holds. In parallel over fixed
// pixel chunks; a run of one triangle's pixels looks it up once, and a set bit is only
// read, so the atomic OR is rare. The result (an OR) is the same for any thread count.
void mark_held(const ImageU32& triangles, uint8_t bit, std::vector<uint8_t>& held) {
  const uint32_t* ids = triangles.data().data();
  uint8_t* mask = held.data();
  parallel_for(triangles.data().size(), size_t(1) << 15, [ids, mask, bit](size_t begin, size_t end) {
    uint32_t last = kNoTriangle;
    for (size_t p = begin; p < end; ++p) {
      const uint32_t t = ids[p];
      if (t == kNoTriangle || t == last) continue;
      last = t;
      std::atomic_ref<uint8_t> h(mask[t]);
      if (!(h.load(std::memory_order_relaxed) & bit)) h.fetch_or(bit, std::memory_order_relaxed);
    }
  });
}

}  // namespace

std::vector<DepthImage> sample_nrr(const Scene& scene, std::span<const Camera> cameras, Redundancy redundancy,
                                   const RayScene* rays, bool shade, float epsilon) {
  assert(redundancy != Redundancy::Visibility || rays != nullptr);
  const bool pixel = redundancy == Redundancy::Pixel;
  std::vector<DepthImage> images;
  images.reserve(cameras.size());  // the tests below point into it
  std::vector<uint8_t> held(pixel ? scene.triangles.size() : 0, 0);
  std::vector<vec3> centers;
  std::vector<uint32_t> order;
  for (size_t i = 0; i < cameras.size(); ++i) {
    RasterOptions options = depth_image_raster_options(shade);
    RasterImages out;
    if (i == 0) {
      // No earlier image: every fragment is kept, I_0 is the conventional image.
      rasterize(scene, cameras[i], options, out, AcceptAllFragments{});
    } else {
      std::vector<RedundancyTest> earlier;
      for (size_t j = 0; j < i; ++j)
        earlier.emplace_back(redundancy, scene, rays, cameras[i], images[j], epsilon);
      // Front-to-back draw order (early z): once a pixel holds a non-redundant fragment,
      // farther fragments fail the depth test before reaching the costly redundancy test.
      // The result does not depend on the order (the depth test orders by (depth, id)).
      if (centers.empty()) centers = cluster_centers(scene);
      front_to_back(scene, centers, cameras[i], order);
      options.triangles = order;
      rasterize(scene, cameras[i], options, out, NonRedundantTest{earlier, pixel ? held.data() : nullptr});
    }
    images.push_back(to_depth_image(cameras[i], std::move(out)));
    if (pixel && i + 1 < cameras.size())
      mark_held(images.back().triangle, uint8_t(1u << std::min<size_t>(i, 7)), held);
  }
  return images;
}

}  // namespace proxima
