// The depth image of one cluster camera (thesis ch. 4 §4.4–4.5, step 3b of Algorithm 6):
// the scene rasterized from the cluster camera, everything behind its near (clip) plane
// discarded, and the culling that keeps a frame's many cluster cameras from each drawing
// the whole scene.
//
// Culling is exact: a triangle is left out only when no fragment of it could be written —
// its block's bounds lie outside the image's frustum (beyond one pixel of margin), before
// the near or beyond the far plane, wholly behind the clip plane, or project between pixel
// centres (coverage is decided at pixel centres) — so the images with
// and without culling are bit-identical (test ClusterDepthImage.CullingIsExact). The
// rasterizer's result does not depend on draw order (rasterizer.h: per pixel the
// lexicographically smallest (depth, triangle id) of the kept fragments), so drawing a
// subset in any order gives the same image.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/cluster_camera.h"
#include "proxima/reflect/scene_lod.h"
#include "proxima/scene/scene.h"

namespace proxima {

// A two-level hierarchy over the scene for culling: objects, and within each object runs
// of at most `block_triangles` consecutive triangles (a mesh's consecutive triangles are
// neighbours, so a run's bounds are tight). Blocks of object o are
// object_first_block[o] .. object_first_block[o + 1] − 1.
struct TriangleBlocks {
  std::vector<uint32_t> first;               // per block: first triangle id
  std::vector<uint32_t> count;               // per block: triangles
  std::vector<Bounds3> bounds;               // per block: world bounds of its vertices
  std::vector<uint32_t> first_vertex;        // per block: lowest vertex index of its triangles
  std::vector<uint32_t> vertex_count;        // per block: highest − lowest + 1
  std::vector<uint32_t> object_first_block;  // per object, plus one end entry
  std::vector<Bounds3> object_bounds;        // per object: union of its blocks' bounds
};

// Blocks of the scene as posed (call again after moving objects). Scenes without objects
// give no blocks (cull_cluster_triangles then keeps everything).
TriangleBlocks triangle_blocks(const Scene& scene, int block_triangles = 64);

// The blocks (as triangle runs, ascending) that may write a fragment into the image of
// `camera`: bounds inside the frustum, not wholly on the discarded side of the clip plane,
// and not projecting between pixel centres. Objects are tested first by their bounds, then their blocks. `excluded_object` (kNoObject for none) is left out entirely. `margin`
// (meters, ≥ 0) widens every plane test so that float rounding can never cull a triangle
// that would show. Returns false when the scene has no objects (nothing can be culled;
// `out` is then empty and means "the whole scene").
bool cull_cluster_triangles(const Scene& scene, const TriangleBlocks& blocks, const ClusterCamera& camera, uint32_t excluded_object, float margin,
                            std::vector<TriangleRun>& out);

// The blocks of `object` alone that may write a fragment into the image of `camera` (the
// tests of cull_cluster_triangles). False when the scene has no objects.
bool cull_cluster_object(const Scene& scene, const TriangleBlocks& blocks, const ClusterCamera& camera, uint32_t object,
                         float margin, std::vector<TriangleRun>& out);
// The same with levels of detail: `blocks` of lod_draw_scene(lod, …), `excluded_object` a
// source object. Each source object is drawn at the coarsest level whose cell is at most
// `lod_texels` texel footprints at the nearest depth of its bounds (footprint = depth /
// focal length in pixels), level 0 (the exact triangles) when no level's cell is small
// enough. Not exact: the image differs from the exact one by up to about a cell.
bool cull_cluster_triangles_lod(const SceneLod& lod, const TriangleBlocks& blocks, const ClusterCamera& camera,
                                uint32_t excluded_object, float margin, float lod_texels, std::vector<TriangleRun>& out);

// Which triangles a cluster image draws: all of the scene but `excluded_object`
// (`culled` = false), or exactly the runs `triangles` (`culled` = true, e.g. from
// cull_cluster_triangles, which already left the excluded object out).
struct ClusterDrawList {
  bool culled = false;
  std::span<const TriangleRun> triangles;
  uint32_t excluded_object = kNoObject;  // used when not culled
  std::span<const Bounds3> object_bounds;  // as RasterOptions::object_bounds
  // Meters (> 0, far above float rounding): triangles wholly this far in front of the clip
  // plane keep every fragment without the per-fragment clip test (the same image).
  float clip_margin = kInf;
  // Drawing a SceneLod's levels (the scene passed is lod_draw_scene): per drawn triangle the
  // source triangle, which the images' triangle ids are mapped to. Empty = the scene's own.
  std::span<const uint32_t> source_triangle;
};

// First layer: depth (−z_cam), triangle id and barycentrics of the nearest surface in
// front of the clip plane (dot(x − P_c, n_c) > clip_offset) at each texel of
// camera.camera's image.
RasterStats rasterize_cluster_image(const Scene& scene, const ClusterCamera& camera, const ClusterDrawList& draw,
                                    RasterImages& out);

// Second layer: the nearest front face more than `separation` (relative depth) behind
// `first` (the first layer of the same camera and draw list), in front of the clip plane.
RasterStats rasterize_cluster_second_layer(const Scene& scene, const ClusterCamera& camera,
                                           const ClusterDrawList& draw, const RasterImages& first,
                                           float separation, RasterImages& out);

// Own layer of a curved cluster: what the draw list holds (its own reflector) in front of
// the clip plane and more than `separation` (meters) behind `start_depth` (1 channel, per
// texel the smallest depth of the cluster's own surface points there; 0 where none), i.e.
// without the nearest surface its rays start on and what lies between it and the camera.
RasterStats rasterize_cluster_own_layer(const Scene& scene, const ClusterCamera& camera, const ClusterDrawList& draw,
                                        const ImageF& start_depth, float separation, RasterImages& out);

}  // namespace proxima
