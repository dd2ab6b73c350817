// Cluster depth images and their culling (cluster_depth_image.h).
// Paper: thesis ch. 4 §4.4–4.5 (the cluster image D rasterized from camera K with the
// fitting plane as near plane). The culling is not in the thesis, whose GPU draws the whole
// scene per cluster; on the CPU the per-cluster geometry pass over every triangle cost
// more than the rays it answers, so each cluster draws only the blocks its frustum holds.
#include "proxima/reflect/cluster_depth_image.h"

#include <algorithm>
#include <cmath>

#include "proxima/core/camera_projection.h"
#include "proxima/core/parallel.h"
#include "proxima/raster/depth_peeling.h"

namespace proxima {

namespace {

// Pixels of slack around a block's projection for the pixel-centre test.
constexpr float kCentreSlackPx = 0.01f;

// A half-space value(x) = dot(n, x) + d; a box is outside when its largest value is below
// −margin.
struct HalfSpace {
  vec3 n;
  float d;

  bool box_outside(const Bounds3& b, float margin) const {
    float most = d;
    for (int i = 0; i < 3; ++i) most += n[i] > 0.0f ? n[i] * b.max[i] : n[i] * b.min[i];
    return most < -margin;
  }
};

// The cluster image's volume: four sides of the frustum one pixel wider than the image,
// near and far planes (W = −z_cam in [near, far], as the rasterizer clips), and the clip
// plane that the fragment test applies.
struct ClusterVolume {
  HalfSpace planes[7];

  explicit ClusterVolume(const ClusterCamera& k) {
    const Camera& cam = k.camera;
    const vec3 e = cam.position, fwd = camera_forward(cam), right = camera_right(cam), up = camera_up(cam);
    const float f = focal_length_px(cam);
    // Pixel x = f·x_c / W + width/2 lies in [−1, width + 1] ⟺ |x_c| ≤ tx·W.
    const float tx = (0.5f * float(cam.width) + 1.0f) / f, ty = (0.5f * float(cam.height) + 1.0f) / f;
    auto through_eye = [&](vec3 n) { return HalfSpace{n, -glm::dot(n, e)}; };
    planes[0] = through_eye(right + tx * fwd);
    planes[1] = through_eye(-right + tx * fwd);
    planes[2] = through_eye(up + ty * fwd);
    planes[3] = through_eye(-up + ty * fwd);
    planes[4] = HalfSpace{fwd, -glm::dot(fwd, e) - cam.near};
    planes[5] = HalfSpace{-fwd, glm::dot(fwd, e) + cam.far};
    planes[6] = HalfSpace{k.plane_normal, -glm::dot(k.plane_normal, k.plane_point) - k.clip_offset};
  }

  bool box_outside(const Bounds3& b, float margin) const {
    if (b.empty()) return true;
    for (const HalfSpace& p : planes)
      if (p.box_outside(b, margin)) return true;
    return false;
  }
};

// Whether a box wholly in front of the camera projects between pixel centres: the
// rectangle around its projected corners holds no centre (x + 0.5, y + 0.5) along one axis,
// so no triangle inside it covers one (coverage is decided at pixel centres). `slack`
// (pixels) covers the 1/4096-pixel snapping and float rounding.
bool between_pixel_centres(const CameraProjection& projection, float near, const Bounds3& b, float slack) {
  vec2 lo(kInf), hi(-kInf);
  for (int i = 0; i < 8; ++i) {
    const auto p = projection(b.corner(i));
    if (!p || !(p->depth > near)) return false;
    lo = glm::min(lo, p->pixel);
    hi = glm::max(hi, p->pixel);
  }
  for (int axis = 0; axis < 2; ++axis)
    if (std::floor(hi[axis] + slack - 0.5f) < std::ceil(lo[axis] - slack - 0.5f)) return true;
  return false;
}

// Keeps fragments in front of the clip plane (the fitting plane or below a curved cluster).
// A triangle whose three vertices lie in front of it by more than `margin` keeps all its
// fragments (each is a point of the triangle up to the rounding of its pixel and depth,
// far below the margin), so those skip the per-fragment test with the same result.
struct InFrontOfClipPlane {
  const Scene& scene;
  const ClusterCamera& k;
  float margin;
  CameraProjection projection{k.camera};

  bool operator()(const Fragment& fr) const {
    const vec3 x = projection.unproject(vec2(float(fr.x) + 0.5f, float(fr.y) + 0.5f), fr.depth);
    return glm::dot(x - k.plane_point, k.plane_normal) > k.clip_offset;
  }
  bool keeps_all(uint32_t triangle) const {
    const uvec3 idx = scene.triangles[triangle];
    for (int i = 0; i < 3; ++i)
      if (!(glm::dot(scene.positions[idx[i]] - k.plane_point, k.plane_normal) > k.clip_offset + margin)) return false;
    return true;
  }
};

// Appends the blocks of object `o` (of the scene `blocks` was built from) that may write a
// fragment into the image.
void keep_object_blocks(const ClusterVolume& volume, const CameraProjection& projection, float near,
                        const TriangleBlocks& blocks, uint32_t o, float margin, std::vector<TriangleRun>& out) {
  for (uint32_t i = blocks.object_first_block[o]; i < blocks.object_first_block[o + 1]; ++i) {
    if (volume.box_outside(blocks.bounds[i], margin)) continue;
    if (between_pixel_centres(projection, near, blocks.bounds[i], kCentreSlackPx)) continue;
    out.push_back({blocks.first[i], blocks.count[i], blocks.first_vertex[i], blocks.vertex_count[i]});
  }
}

// Triangle ids of a level-of-detail draw back to the source triangles they stand for.
void to_source_triangles(std::span<const uint32_t> source_triangle, ImageU32& triangle) {
  if (source_triangle.empty()) return;
  for (uint32_t& t : triangle.data())
    if (t != kNoTriangle) t = source_triangle[t];
}

// Images of an empty draw list: what the rasterizer leaves where nothing is drawn.
RasterStats empty_images(const Camera& cam, RasterImages& out) {
  out.depth = ImageF(cam.width, cam.height, 1, kInf);
  out.triangle = ImageU32(cam.width, cam.height, 1, kNoTriangle);
  out.barycentric = ImageF(cam.width, cam.height, 2, 0.0f);
  return RasterStats{};
}

RasterOptions cluster_raster_options(const Scene& scene, const ClusterDrawList& draw,
                                     std::vector<uint32_t>& others) {
  RasterOptions ro;
  ro.outputs = kRasterDepth | kRasterTriangle | kRasterBarycentric;
  ro.object_bounds = draw.object_bounds;
  if (draw.culled) {
    ro.triangle_runs = draw.triangles;
  } else if (draw.excluded_object != kNoObject) {
    for (uint32_t o = 0; o < scene.objects.size(); ++o)
      if (o != draw.excluded_object) others.push_back(o);
    ro.objects = others;
  }
  return ro;
}

// Whether the draw list holds nothing (an empty id or object list would mean the whole
// scene to the rasterizer).
bool draws_nothing(const Scene& scene, const ClusterDrawList& draw) {
  if (draw.culled) return draw.triangles.empty();
  return draw.excluded_object != kNoObject && scene.objects.size() == 1 && draw.excluded_object == 0;
}

}  // namespace

TriangleBlocks triangle_blocks(const Scene& scene, int block_triangles) {
  TriangleBlocks out;
  const uint32_t size = uint32_t(std::max(1, block_triangles));
  out.object_first_block.assign(scene.objects.size() + 1, 0);
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& obj = scene.objects[o];
    out.object_first_block[o] = uint32_t(out.first.size());
    for (uint32_t t = 0; t < obj.triangle_count; t += size) {
      out.first.push_back(obj.first_triangle + t);
      out.count.push_back(std::min(size, obj.triangle_count - t));
    }
  }
  out.object_first_block.back() = uint32_t(out.first.size());
  out.bounds.resize(out.first.size());
  out.first_vertex.resize(out.first.size());
  out.vertex_count.resize(out.first.size());
  parallel_for(out.first.size(), 64, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      Bounds3 box;
      uint32_t lo = ~0u, hi = 0;
      for (uint32_t t = out.first[i]; t < out.first[i] + out.count[i]; ++t) {
        const uvec3 idx = scene.triangles[t];
        for (int k = 0; k < 3; ++k) {
          box.extend(scene.positions[idx[k]]);
          lo = std::min(lo, idx[k]);
          hi = std::max(hi, idx[k]);
        }
      }
      out.bounds[i] = box;
      out.first_vertex[i] = lo;
      out.vertex_count[i] = hi - lo + 1;
    }
  });
  out.object_bounds.resize(scene.objects.size());
  for (size_t o = 0; o < scene.objects.size(); ++o)
    for (uint32_t i = out.object_first_block[o]; i < out.object_first_block[o + 1]; ++i)
      out.object_bounds[o].extend(out.bounds[i]);
  return out;
}

bool cull_cluster_triangles(const Scene& scene, const TriangleBlocks& blocks, const ClusterCamera& camera,
                            uint32_t excluded_object, float margin, std::vector<TriangleRun>& out) {
  out.clear();
  if (scene.objects.empty() || blocks.object_first_block.size() != scene.objects.size() + 1) return false;
  const ClusterVolume volume(camera);
  const CameraProjection projection(camera.camera);
  for (uint32_t o = 0; o < scene.objects.size(); ++o) {
    if (o == excluded_object || volume.box_outside(blocks.object_bounds[o], margin)) continue;
    keep_object_blocks(volume, projection, camera.camera.near, blocks, o, margin, out);
  }
  return true;
}

bool cull_cluster_object(const Scene& scene, const TriangleBlocks& blocks, const ClusterCamera& camera, uint32_t object,
                         float margin, std::vector<TriangleRun>& out) {
  out.clear();
  if (scene.objects.empty() || blocks.object_first_block.size() != scene.objects.size() + 1) return false;
  const ClusterVolume volume(camera);
  if (object < scene.objects.size() && !volume.box_outside(blocks.object_bounds[object], margin))
    keep_object_blocks(volume, CameraProjection(camera.camera), camera.camera.near, blocks, object, margin, out);
  return true;
}

bool cull_cluster_triangles_lod(const SceneLod& lod, const TriangleBlocks& blocks, const ClusterCamera& camera,
                                uint32_t excluded_object, float margin, float lod_texels, std::vector<TriangleRun>& out) {
  out.clear();
  if (lod.source_objects == 0 || blocks.object_first_block.size() != lod.objects.size() + 1) return false;
  const ClusterVolume volume(camera);
  const CameraProjection projection(camera.camera);
  const Camera& cam = camera.camera;
  const vec3 fwd = camera_forward(cam);
  // A texel's footprint at depth z is z / focal (at the image centre; larger off-axis).
  const float cell_per_depth = lod_texels / focal_length_px(cam);
  for (uint32_t o = 0; o < lod.source_objects; ++o) {
    const Bounds3& box = blocks.object_bounds[lod.object(0, o)];
    if (o == excluded_object || volume.box_outside(box, margin)) continue;
    float nearest = kInf;
    for (int i = 0; i < 8; ++i) nearest = std::min(nearest, glm::dot(box.corner(i) - cam.position, fwd));
    const float cell_max = std::max(nearest, cam.near) * cell_per_depth;
    uint32_t level = 0;
    while (level < lod.cell.size() && lod.cell[level] <= cell_max) ++level;
    keep_object_blocks(volume, projection, cam.near, blocks, lod.object(level, o), margin, out);
  }
  return true;
}

RasterStats rasterize_cluster_image(const Scene& scene, const ClusterCamera& camera, const ClusterDrawList& draw,
                                    RasterImages& out) {
  if (draws_nothing(scene, draw)) return empty_images(camera.camera, out);
  std::vector<uint32_t> others;
  const RasterOptions ro = cluster_raster_options(scene, draw, others);
  const RasterStats stats = rasterize(scene, camera.camera, ro, out, InFrontOfClipPlane{scene, camera, draw.clip_margin});
  to_source_triangles(draw.source_triangle, out.triangle);
  return stats;
}

RasterStats rasterize_cluster_second_layer(const Scene& scene, const ClusterCamera& camera,
                                           const ClusterDrawList& draw, const RasterImages& first,
                                           float separation, RasterImages& out) {
  if (draws_nothing(scene, draw)) return empty_images(camera.camera, out);
  std::vector<uint32_t> others;
  RasterOptions ro = cluster_raster_options(scene, draw, others);
  // Back faces are culled so a closed occluder's far side does not take the place of what
  // it hides.
  ro.cull = CullMode::Back;
  const BehindLayerTest behind{first.depth, first.triangle, separation};
  const InFrontOfClipPlane in_front{scene, camera, draw.clip_margin};
  const RasterStats stats =
      rasterize(scene, camera.camera, ro, out, [&](const Fragment& fr) { return behind(fr) && in_front(fr); });
  to_source_triangles(draw.source_triangle, out.triangle);
  return stats;
}

RasterStats rasterize_cluster_own_layer(const Scene& scene, const ClusterCamera& camera, const ClusterDrawList& draw,
                                        const ImageF& start_depth, float separation, RasterImages& out) {
  if (draws_nothing(scene, draw)) return empty_images(camera.camera, out);
  std::vector<uint32_t> others;
  const RasterOptions ro = cluster_raster_options(scene, draw, others);
  const InFrontOfClipPlane in_front{scene, camera, draw.clip_margin};
  const int w = start_depth.width();
  const std::span<const float> start = start_depth.data();
  return rasterize(scene, camera.camera, ro, out, [&](const Fragment& fr) {
    return fr.depth > start[size_t(fr.y) * size_t(w) + size_t(fr.x)] + separation && in_front(fr);
  });
}

}  // namespace proxima
