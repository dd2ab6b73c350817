// Sampling a scene with n depth images (thesis ch. 2): conventional images from each
// viewpoint, depth peeling from one viewpoint, and non-redundant rendering (NRR,
// Algorithm 1) with pixel (Algorithm 3) or visibility (Algorithm 2) redundancy.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/depthimage/depth_image.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

enum class Redundancy {
  Pixel,       // Algorithm 3: the sample's reprojection into I_j holds the same triangle
  Visibility,  // Algorithm 2: the segment V_j → sample point is unoccluded (within ε)
};
const char* redundancy_name(Redundancy r);  // "pixel" | "visibility"
// Throws InputError naming `flag` and the valid names for anything else.
Redundancy parse_redundancy(const std::string& name, const char* flag);

// Default ε of the visibility test, relative to the scene's bounding-box diagonal (the
// ray offset of docs/shading.md).
inline constexpr float kVisibilityEpsilon = 1e-4f;

// Is a sample redundant with one image I_j? The sample is given as it is rasterized by
// camera `from` (PPC_i): pixel (x, y), depth d (−z_cam), triangle t.
//  - Pixel: reproject the pixel center at depth d into I_j; redundant iff it lands inside
//    I_j on a pixel holding triangle t.
//  - Visibility: a = the sample's world point; redundant iff a is in V_j's view (inside
//    I_j's image rectangle, depth in [near, far]), t faces V_j (I_j culls back faces, so
//    it cannot see the back of t), and no front-facing triangle is hit on the segment
//    V_j → a closer than ε = epsilon·scene diagonal before a (Algorithm 2's b == a, with
//    b the first hit; back faces are culled by the images, so they do not occlude).
// Holds references: `scene`, `rays` (Visibility only; may be null for Pixel), `from`
// and `against` must outlive it. Thread-safe (const).
class RedundancyTest {
 public:
  RedundancyTest(Redundancy kind, const Scene& scene, const RayScene* rays, const Camera& from,
                 const DepthImage& against, float epsilon = kVisibilityEpsilon);
  bool operator()(int x, int y, float depth, uint32_t triangle) const;
  // operator() on fragments[k] for every bit k of `candidates` (n ≤ 64; bit k of the
  // result set iff redundant), four reprojections at a time for Pixel. The fragments are
  // one row's, as the rasterizer's keep_run gives them (rasterizer.h).
  uint64_t redundant_run(const Fragment* fragments, int n, uint64_t candidates) const;
  // Pixel redundancy only: four fragments (x[k], y) at depths d[k] of one triangle; bit k
  // of the result set iff bit k of `lanes` is and fragment k is redundant. Inline for
  // NRR's run test.
  unsigned redundant4(const int x[4], int y, const float d[4], uint32_t triangle, unsigned lanes) const {
    const Image<uint32_t>& ids = against_->triangle;
    uint32_t at[4];
    lanes &= reproject_.pixel4(x, y, d, ids.width(), ids.height(), at);
    const uint32_t* id = ids.data().data();
    // The compares without branches (the outcome is data-dependent, mispredicted often)
    // so the four loads overlap.
    unsigned same = 0;
    for (int k = 0; k < 4; ++k) same |= unsigned(id[at[k]] == triangle) << k;
    // The triangle's next row run lands about one row down in I_j: fetch that line now
    // (a hint only; any address is harmless).
    __builtin_prefetch(id + at[0] + ids.width());
    return same & lanes;
  }

 private:
  Redundancy kind_;
  const Scene* scene_;
  const RayScene* rays_;
  const Camera* from_;
  const DepthImage* against_;
  Reprojection reproject_;
  float epsilon_;  // absolute, meters
};

// Conventional sampling: one independent depth image per camera.
std::vector<DepthImage> sample_conventional(const Scene& scene, std::span<const Camera> cameras, bool shade);

// Depth peeling (raster/depth_peeling.h, exact (depth, id) order) from one camera:
// exactly `layers` images; layers past the last non-empty one are empty images.
std::vector<DepthImage> sample_peeling(const Scene& scene, const Camera& camera, int layers, bool shade);

// Non-redundant rendering, Algorithm 1: image i is rasterized from cameras[i] with a
// fragment test that discards every fragment redundant with one of the images 0 … i−1.
// The test runs after the depth test and a discarded fragment leaves the pixel
// untouched, so each pixel ends with the nearest NON-redundant fragment (not the nearest
// fragment, which may be redundant). Image 0 is the conventional image.
// `rays` is required for Visibility (the BVH of `scene`), ignored for Pixel.
std::vector<DepthImage> sample_nrr(const Scene& scene, std::span<const Camera> cameras, Redundancy redundancy,
                                   const RayScene* rays, bool shade, float epsilon = kVisibilityEpsilon);

}  // namespace proxima
