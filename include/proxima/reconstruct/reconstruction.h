// Triangle meshes reconstructed from depth images (thesis ch. 3, §3.2): the conventional
// mesh reconstruction (two triangles per 2×2 pixel quad unless a depth discontinuity
// separates the samples) and the hybrid reconstruction of Algorithm 4 (one quad per
// sample, corners from the half-pixel offset image H or from the sample's tangent plane).
//
// Discontinuity criterion (both methods): a point q lies on the same surface as sample s
// (world point p, unit normal n, depth d, reference focal length f pixels) iff
//   |n · (q − p)| ≤ kContinuityTolerance · d / f,
// i.e. q is within one pixel footprint of s's tangent plane. Planes stay continuous at
// any slant (the distance is 0 there), a 1 cm twig is continuous at the thesis' image
// sizes (its curvature moves a point a fraction of a footprint off the plane), and a
// surface in front of or behind another (blade over ground, roof over street) is not.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/depthimage/depth_image.h"
#include "proxima/scene/mesh.h"
#include "proxima/scene/scene.h"

namespace proxima {

// Tolerance of the continuity test, in pixel footprints (d / f) along the normal.
inline constexpr float kContinuityTolerance = 1.0f;

// A tangent-plane corner never moves further than this many pixel footprints (in depth)
// from its sample: a nearly edge-on plane would otherwise put the corner far away
// (85° slant ≈ 11.4 footprints per pixel, half a pixel diagonal ≈ 0.71 px → 8).
inline constexpr float kMaxCornerDepthOffset = 8.0f;

// Continuity test above. `depth` and `focal_px` are of the reference camera.
bool same_surface(vec3 p, vec3 n, float depth, float focal_px, vec3 q);

// Conventional mesh reconstruction: a vertex per sample (at its pixel center and depth)
// and, for every 2×2 pixel quad, the triangles (x,y)(x,y+1)(x+1,y+1) and
// (x+1,y+1)(x+1,y)(x,y) whose three samples are pairwise continuous (same_surface both
// ways). Isolated samples and one-pixel-wide features produce nothing. Triangles are
// counter-clockwise seen from the image's camera. Needs depth, triangle and normal.
Mesh reconstruct_conventional(const DepthImage& image);

// The camera of Algorithm 4's offset image H for camera `c`: same eye, orientation and
// focal length, one pixel wider and taller, so that H's pixel centers are the pixel
// corners of c (H pixel (i, j) center = c's corner (i, j)).
Camera half_pixel_offset_camera(const Camera& c);

struct HybridStats {
  size_t samples = 0;          // samples of I (one quad each)
  size_t quads = 0;            // quads emitted: samples, fewer with merged planar runs
  size_t corners_from_h = 0;   // sample corners taken from H
  size_t corners_fitted = 0;   // sample corners from the tangent plane
  size_t vertices = 0;
};

// Hybrid reconstruction (Algorithm 4) of image I (`image`) with its offset image H
// (`offset`, rendered with half_pixel_offset_camera(image.camera) and the same sampling
// rule as I). Every sample of I becomes the quad c0 c1 c2 c3 over its pixel square
// (corners (x,y), (x,y+1), (x+1,y+1), (x+1,y) on the camera rays through them), split
// into c0c1c2 and c2c3c0, counter-clockwise seen from the camera. Corners are shared:
// at each pixel corner the (up to four) samples around it are grouped by continuity
// with their edge neighbours; a group takes H's sample there if it is on the surface of
// every member, else one vertex at the mean of the members' tangent-plane intersections (each
// clamped to kMaxCornerDepthOffset footprints in depth). So a continuous surface comes
// out watertight and each sample covers exactly its pixel square seen from the camera.
// Needs depth, triangle, normal of both images. Deterministic for any thread count.
//
// merge_planar_runs: consecutive quads of a row that share their corner vertices and whose
// corners all lie within kMergeTolerance footprints of the run's first sample's tangent
// plane become one quad (first quad's left corners, last quad's right corners). The corners
// are on the camera rays through the pixel corners, so on a plane the run's top and bottom
// corners are collinear: the one quad covers the same pixels and the same surface (to
// 2 · kMergeTolerance footprints), and the vertices of the neighbouring rows lie on its
// edges. Fewer triangles for the same shape: what a shadow map of the mesh pays for.
inline constexpr float kMergeTolerance = 1e-3f;
Mesh reconstruct_hybrid(const DepthImage& image, const DepthImage& offset, HybridStats* stats = nullptr,
                        bool merge_planar_runs = false);

// A scene with one object per mesh (no lights, one grey material): what the rasterizer
// and Embree take. Meshes without normals get computed ones.
Scene reconstruction_scene(std::span<const Mesh> meshes, const std::string& name = "reconstruction");

}  // namespace proxima
