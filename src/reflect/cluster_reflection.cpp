// Reflections from screen-space clustered depth images on a reflection frame (reflection_frame.cpp
// holds the frame, the Embree pass over the same rays and the blend).
// Paper: thesis ch. 4, Algorithm 6 (§4.2), with §4.3 clustering (cluster_clustering.cpp),
// §4.4 cluster cameras (cluster_camera.cpp), §4.5 Algorithm 7 (cluster_depth_image_march.cpp),
// §4.6 glossy reflections. Symbols ↔ variables: S ↔ scene, e ↔ frame.camera.position,
// p.rgb_d ↔ frame.base, p.s / p.g ↔ frame.specular / gloss, p.n ↔ frame.normal,
// p.rID ↔ frame.reflector, C ↔ a cluster of ReflectionClusters, K ↔ ClusterCamera,
// D ↔ depth + color (the cluster image), r_i ↔ frame.direction, d_i ↔ one ray's color,
// G(d_i, p.g) ↔ the mean over the lobe rays (the lobe is uniform in solid angle, docs/shading.md).
// Glossy (§4.6): the lobe rays' end points widen the cluster window; the far distance
// D_g = diagonal·(1 − falloff·g_max) is nearer for rougher clusters, and hits in its last
// fade_fraction fade to the environment radiance (what a ray escaping the image gets).
#include "proxima/reflect/cluster_reflection.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/raster/rasterizer.h"
#include "proxima/reflect/cluster_camera.h"
#include "proxima/reflect/cluster_depth_image.h"
#include "proxima/reflect/depth_image_march.h"
#include "proxima/reflect/hit_shading.h"
#include "proxima/trace/object_bvh.h"
#include "proxima/scene/shading.h"

namespace proxima {

namespace {

// Culling margin, as a fraction of the scene diagonal: wider than any float rounding of a
// plane test, so culling never drops a triangle that would show.
constexpr float kCullMargin = 1e-3f;

// Wall-clock and process CPU time of a step, added to the step's figures.
struct PhaseClock {
  Stopwatch wall;
  double cpu0 = process_cpu_ms();
  void restart() {
    wall.restart();
    cpu0 = process_cpu_ms();
  }
  double wall_ms() const { return wall.elapsed_ms(); }
  void add_to(double& wall_total, double& cpu_total) const {
    wall_total += wall.elapsed_ms();
    cpu_total += process_cpu_ms() - cpu0;
  }
};

// Bilinear color of the texels around continuous pixel `s` that lie on the hit surface
// (depth within 5% of `depth`); the nearest texel when none does.
vec3 lookup_color(const ImageF& color, const ImageF& depth, vec2 s, float hit_depth) {
  const int w = color.width(), h = color.height();
  const float fx = s.x - 0.5f, fy = s.y - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float tx = fx - float(x0), ty = fy - float(y0);
  vec3 sum(0.0f);
  float weight = 0.0f;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      int x = x0 + i, y = y0 + j;
      if (x < 0 || y < 0 || x >= w || y >= h) continue;
      float d = depth.at(x, y);
      if (!(std::abs(d - hit_depth) <= 0.05f * hit_depth)) continue;
      float wt = (i ? tx : 1.0f - tx) * (j ? ty : 1.0f - ty);
      sum += wt * vec3(color.at(x, y, 0), color.at(x, y, 1), color.at(x, y, 2));
      weight += wt;
    }
  if (weight > 0.0f) return sum / weight;
  int x = std::clamp(int(s.x), 0, w - 1), y = std::clamp(int(s.y), 0, h - 1);
  return vec3(color.at(x, y, 0), color.at(x, y, 1), color.at(x, y, 2));
}

// Marks in `needed` (one byte per texel of `depth`) every texel lookup_color may read for
// the hits of rays whose answer is not `env`: the 2×2 bilinear texels and the nearest one.
void mark_lookup_texels(const ImageF& depth, std::span<const DepthImageHit> hits, std::span<const uint8_t> answer,
                        uint8_t env, std::vector<uint8_t>& needed) {
  const int w = depth.width(), h = depth.height();
  needed.assign(size_t(w) * size_t(h), 0);
  for (size_t r = 0; r < hits.size(); ++r) {
    if (answer[r] == env) continue;
    const vec2 s = hits[r].pixel;
    const int x0 = int(std::floor(s.x - 0.5f)), y0 = int(std::floor(s.y - 0.5f));
    for (int y = std::max(0, y0); y <= std::min(h - 1, y0 + 1); ++y)
      for (int x = std::max(0, x0); x <= std::min(w - 1, x0 + 1); ++x) needed[size_t(y) * size_t(w) + size_t(x)] = 1;
    const int x = std::clamp(int(s.x), 0, w - 1), y = std::clamp(int(s.y), 0, h - 1);
    needed[size_t(y) * size_t(w) + size_t(x)] = 1;
  }
}

// Shades the needed texels of a cluster image that hold a surface (shade_reflected_point
// towards the camera, a row's texels together); the others stay black. Returns the texels shaded.
uint64_t shade_texels(const Scene& scene, int area_light_samples, const Camera& cam, const RasterImages& images,
                      std::span<const uint8_t> needed, ImageF& color) {
  color = ImageF(cam.width, cam.height, 3, 0.0f);
  std::vector<uint64_t> row_count(size_t(cam.height), 0);
  const LightTable lights(scene, area_light_samples);
  parallel_for(size_t(cam.height), 8, [&](size_t y0, size_t y1) {
    HitShading shading(lights);
    std::vector<int> shaded_x;
    for (int y = int(y0); y < int(y1); ++y) {
      shading.clear();
      shaded_x.clear();
      for (int x = 0; x < cam.width; ++x) {
        const uint32_t t = images.triangle.at(x, y);
        if (t == kNoTriangle || !needed[size_t(y) * size_t(cam.width) + size_t(x)]) continue;
        const float u = images.barycentric.at(x, y, 0), v = images.barycentric.at(x, y, 1);
        shading.add_hit(scene, t, u, v, cam.position - triangle_point(scene, t, u, v));
        shaded_x.push_back(x);
      }
      shading.finish();
      for (size_t k = 0; k < shaded_x.size(); ++k)
        for (int ch = 0; ch < 3; ++ch) color.at(shaded_x[k], y, ch) = shading.color[k][ch];
      row_count[size_t(y)] = shaded_x.size();
    }
  });
  uint64_t total = 0;
  for (uint64_t n : row_count) total += n;
  return total;
}

// Whether some texel of the 3×3 around continuous pixel `s` holds `triangle` or a depth
// for which depth_ok(depth) holds.
template <class DepthOk>
bool any_texel_near(const RasterImages& image, vec2 s, uint32_t triangle, DepthOk depth_ok) {
  const int w = image.depth.width(), h = image.depth.height();
  const int cx = int(s.x), cy = int(s.y);
  for (int y = std::max(0, cy - 1); y <= std::min(h - 1, cy + 1); ++y)
    for (int x = std::max(0, cx - 1); x <= std::min(w - 1, cx + 1); ++x)
      if (image.triangle.at(x, y) == triangle || depth_ok(image.depth.at(x, y))) return true;
  return false;
}

// Whether the surface point at continuous pixel `s`, depth `z`, on `triangle`, shows in the
// image: some texel of the 3×3 around `s` holds that triangle or a depth ≥ 0.99·z.
bool visible_near(const RasterImages& image, vec2 s, float z, uint32_t triangle) {
  return any_texel_near(image, s, triangle, [z](float d) { return d >= 0.99f * z; });
}

// Whether the image holds that point: the triangle or a depth within 1% of z (an empty
// texel holds nothing).
bool held_near(const RasterImages& image, vec2 s, float z, uint32_t triangle) {
  return any_texel_near(image, s, triangle, [z](float d) { return std::abs(d - z) <= 0.01f * z; });
}

// Per texel of the cluster image the smallest depth of the cluster's surface points that
// project within `radius(depth)` texels of it (0 where none): the nearest surface its rays
// start on there.
template <class Radius>
ImageF start_depths(const CameraProjection& projection, int width, int height, std::span<const uint32_t> members,
                    std::span<const vec3> position, Radius radius) {
  ImageF start(width, height, 1, 0.0f);
  for (uint32_t i : members) {
    const auto p = projection(position[i]);
    if (!p) continue;
    const int r = radius(p->depth);
    const int cx = int(std::floor(p->pixel.x)), cy = int(std::floor(p->pixel.y));
    for (int y = std::max(0, cy - r); y <= std::min(height - 1, cy + r); ++y)
      for (int x = std::max(0, cx - r); x <= std::min(width - 1, cx + r); ++x)
        start.at(x, y) = start.at(x, y) > 0.0f ? std::min(start.at(x, y), p->depth) : p->depth;
  }
  return start;
}

// Narrows [t0, t1] to the part of the ray inside box `b`; false when that is empty.
bool clip_to_box(const Bounds3& b, vec3 origin, vec3 dir, float& t0, float& t1) {
  for (int a = 0; a < 3; ++a) {
    if (std::abs(dir[a]) < 1e-12f) {
      if (origin[a] < b.min[a] || origin[a] > b.max[a]) return false;
      continue;
    }
    float ta = (b.min[a] - origin[a]) / dir[a], tb = (b.max[a] - origin[a]) / dir[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 < t1;
}

// Ray parameters [t0, t1] inside the cluster image's volume: in front of the near (clip)
// plane, within the camera's depth range and within the far distance. False when empty.
bool clip_ray(const ClusterCamera& k, vec3 origin, vec3 dir, float far_distance, float& t0, float& t1) {
  t0 = 0.0f;
  t1 = far_distance;
  auto keep_above = [&](float value_at_0, float slope, float bound) {  // value(t) ≥ bound
    if (std::abs(slope) < 1e-12f) return value_at_0 >= bound;
    float t = (bound - value_at_0) / slope;
    if (slope > 0.0f) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    return true;
  };
  const vec3 fwd = camera_forward(k.camera);
  const float z0 = glm::dot(origin - k.camera.position, fwd), dz = glm::dot(dir, fwd);
  const float h0 = glm::dot(origin - k.plane_point, k.plane_normal), dh = glm::dot(dir, k.plane_normal);
  if (!keep_above(h0, dh, k.clip_offset)) return false;
  if (!keep_above(z0, dz, 1.001f * k.camera.near)) return false;
  if (!keep_above(-z0, -dz, -0.999f * k.camera.far)) return false;
  return t0 < t1;
}

// A march without fill over `depth` that skips runs of texels the ray stays in front of by
// their block minima (block > 0; kept in `block_min`).
MarchOptions block_march(const ImageF& depth, int block, ImageF& block_min) {
  MarchOptions o;
  o.block = block;
  if (block > 0) {
    block_min = depth_block_min(depth, block);
    o.block_min = &block_min;
  }
  return o;
}

// Calls f(i, r) for every ray r of every sample i of a cluster, in parallel over its samples.
template <typename F>
void for_each_cluster_ray(const ReflectionFrame& frame, std::span<const uint32_t> members, F&& f) {
  parallel_for(members.size(), 64, [&](size_t b, size_t e) {
    for (size_t m = b; m < e; ++m)
      for (uint32_t r = frame.first_ray[members[m]]; r < frame.first_ray[members[m] + 1]; ++r) f(members[m], r);
  });
}

}  // namespace

ClusterReflections render_cluster_reflections(const Scene& scene, const ReflectionFrame& frame,
                                              const ClusterReflectionOptions& options,
                                              std::span<const Bounds3> object_bounds,
                                              const TracedReflections* reference) {
  ClusterReflections out;
  ClusterFrameStats& st = out.stats;
  const size_t n = frame.sample_count();
  out.radiance.assign(n, vec3(0.0f));
  st.reflective_samples = n;
  if (n == 0) return out;
  const float epsilon = kReflectionRayOffset * frame.scene_diagonal;
  const int sw = frame.sample_camera.width;

  // Step 2: clusters; step 3a needs each cluster's mean pixel footprint p: the distance
  // between horizontally and vertically neighbouring samples of the cluster in the
  // tangent plane of the first.
  PhaseClock clock;
  ReflectionClusters clusters = cluster_reflections(frame.normal, frame.reflector, options.clustering);
  const size_t nc = clusters.count();
  st.clusters = nc;
  clock.add_to(st.clustering_ms, st.clustering_cpu_ms);
  clock.restart();
  std::vector<int32_t> sample_at(frame.base.pixel_count(), -1);
  for (size_t i = 0; i < n; ++i) sample_at[frame.pixel[i]] = int32_t(i);
  std::vector<double> footprint_sum(nc, 0.0);
  std::vector<uint32_t> footprint_count(nc, 0);
  std::vector<float> footprint(nc, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t px = frame.pixel[i];
    const int x = int(px % uint32_t(sw));
    for (uint32_t next : {x + 1 < sw ? px + 1 : px, px + uint32_t(sw)}) {
      if (next == px || next >= sample_at.size() || sample_at[next] < 0) continue;
      const size_t j = size_t(sample_at[next]);
      if (clusters.cluster_of[j] != clusters.cluster_of[i]) continue;
      vec3 d = frame.position[j] - frame.position[i];
      d -= glm::dot(d, frame.normal[i]) * frame.normal[i];
      footprint_sum[clusters.cluster_of[i]] += glm::length(d);
      ++footprint_count[clusters.cluster_of[i]];
    }
  }
  const float focal = focal_length_px(frame.sample_camera);
  std::vector<std::optional<ClusterCamera>> cameras(nc);
  std::vector<float> far_distance(nc);
  std::vector<float> cluster_gloss(nc, 0.0f);
  {
    std::vector<vec3> points, normals, ends;
    for (size_t c = 0; c < nc; ++c) {
      points.clear();
      normals.clear();
      ends.clear();
      for (uint32_t i : clusters.cluster(c)) cluster_gloss[c] = std::max(cluster_gloss[c], frame.gloss[i]);
      far_distance[c] = frame.scene_diagonal *
                        (cluster_gloss[c] > 0.0f ? std::max(0.05f, 1.0f - options.glossy_far_falloff * cluster_gloss[c]) : 1.0f);
      for (uint32_t i : clusters.cluster(c)) {
        points.push_back(frame.position[i]);
        normals.push_back(frame.normal[i]);
        for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r)
          ends.push_back(frame.origin[i] + far_distance[c] * frame.direction[r]);
      }
      ClusterCameraInput in;
      in.points = points;
      in.normals = normals;
      in.ray_ends = ends;
      in.eye = frame.camera.position;
      // A lone pixel: its footprint at its distance from the eye.
      in.pixel_footprint = footprint_count[c] > 0
                               ? float(footprint_sum[c] / double(footprint_count[c]))
                               : glm::length(points[0] - frame.camera.position) / focal;
      in.resolution_scale = options.resolution_scale;
      in.max_image_side = options.max_image_side;
      in.plane_tolerance = epsilon;
      footprint[c] = in.pixel_footprint;
      cameras[c] = build_cluster_camera(in);
      if (cameras[c] && cameras[c]->planar) {
        ++st.planar_clusters;
        st.planar_samples += points.size();
      }
    }
  }
  clock.add_to(st.cameras_ms, st.cameras_cpu_ms);

  out.cluster = clusters.cluster_of;
  out.flags.assign(n, 0);
  out.occlusion_cause.assign(n, uint8_t(OcclusionCause::None));
  // Culling hierarchy of the posed scene, built once per frame (part of step 3b).
  clock.restart();
  // With levels of detail the cluster images are drawn from a scene holding every level.
  std::optional<SceneLod> own_lod;
  const SceneLod* lod = nullptr;
  if (options.cull && options.lod_texels > 0.0f && !scene.objects.empty()) {
    if (!options.lod) own_lod = build_scene_lod(scene, lod_cells(frame.scene_diagonal, kClusterLodLevels));
    lod = options.lod ? options.lod : &*own_lod;
  }
  const Scene lod_scene = lod ? lod_draw_scene(*lod, scene) : Scene{};
  const Scene& draw_scene = lod ? lod_scene : scene;
  const TriangleBlocks blocks = options.cull ? triangle_blocks(draw_scene) : TriangleBlocks{};
  // The own layer draws the exact reflector: its blocks come from the scene itself.
  const TriangleBlocks exact_blocks = options.cull && lod && options.own_layer ? triangle_blocks(scene) : TriangleBlocks{};
  const TriangleBlocks& own_blocks = lod ? exact_blocks : blocks;
  const float cull_margin = kCullMargin * frame.scene_diagonal;
  clock.add_to(st.depth_images_ms, st.depth_images_cpu_ms);
  RasterImages images, back, own;
  std::vector<TriangleRun> own_runs;
  std::vector<Bounds3> own_box(scene.objects.size());  // the reflectors' bounds, as needed
  std::vector<std::optional<ObjectBvh>> own_bvh(scene.objects.size());  // built as needed
  ImageF color;
  std::vector<TriangleRun> drawn;
  std::vector<uint8_t> needed;
  // Per-ray buffers of a cluster, reused across clusters: allocated per cluster they cost
  // more in page faults and zeroing than the march of a small cluster.
  enum Answer : uint8_t { kHit, kFill, kEnv, kSecond, kOwn };
  std::vector<uint8_t> ray_occluded, answer, needs_second;
  std::vector<float> second_t, own_t;
  std::vector<uint32_t> own_triangle;
  std::vector<vec3> ray_color;
  std::vector<DepthImageHit> ray_hit;
  out.cameras = cameras;
  for (size_t c = 0; c < nc; ++c) {
    const std::span<const uint32_t> members = clusters.cluster(c);
    st.max_cluster_samples = std::max<uint64_t>(st.max_cluster_samples, members.size());
    if (!cameras[c]) {
      for (uint32_t i : members) {
        out.flags[i] |= kEnvFallback;
        vec3 sum(0.0f);
        for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r)
          sum += environment_radiance(scene.environment, frame.direction[r]);
        out.radiance[i] = sum / float(frame.first_ray[i + 1] - frame.first_ray[i]);
      }
      continue;
    }
    const ClusterCamera& k = *cameras[c];
    const Camera& cam = k.camera;
    const CameraProjection projection(cam);

    // Step 3b: the cluster image, everything in front of the near (clip) plane. A curved
    // cluster's own reflector bulges in front of its fitting plane and would only hide what
    // its rays hit; it is left out here (convex reflectors do not see themselves) and drawn
    // into the own layer below.
    clock.restart();
    ClusterDrawList draw;
    draw.excluded_object = k.planar ? kNoObject : clusters.reflector[c];
    draw.object_bounds = object_bounds;
    draw.clip_margin = cull_margin;
    draw.culled = options.cull && (lod ? cull_cluster_triangles_lod(*lod, blocks, k, draw.excluded_object, cull_margin,
                                                                    options.lod_texels, drawn)
                                       : cull_cluster_triangles(scene, blocks, k, draw.excluded_object, cull_margin, drawn));
    if (lod) {
      draw.object_bounds = blocks.object_bounds;
      draw.source_triangle = lod->source_triangle;
    }
    draw.triangles = drawn;
    RasterStats rs = rasterize_cluster_image(draw_scene, k, draw, images);
    st.objects_drawn += rs.objects_drawn;
    st.triangles_drawn += rs.triangles_submitted;
    st.texels += uint64_t(cam.width) * uint64_t(cam.height);
    clock.add_to(st.depth_images_ms, st.depth_images_cpu_ms);

    // Step 3c: every ray of every pixel against the image.
    clock.restart();
    const float far = far_distance[c];
    const bool glossy = cluster_gloss[c] > 0.0f;
    MarchOptions march;
    march.fill_behind = true;
    // Block minima let the march skip runs of texels the ray stays in front of.
    const int block = options.march_block;
    march.block = block;
    // Lobe rays, averaged per sample, march a coarser image of block nearest depths.
    march.coarse = glossy ? options.glossy_march_coarse : 1;
    const ImageF block_min = block > 0 && march.coarse <= 1 ? depth_block_min(images.depth, block) : ImageF();
    if (block > 0 && march.coarse <= 1) march.block_min = &block_min;
    const ImageF coarse_depth = march.coarse > 1 ? depth_block_min(images.depth, march.coarse) : ImageF();
    const ImageF& march_depth = march.coarse > 1 ? coarse_depth : images.depth;
    const uint32_t ray_base = frame.first_ray[members.front()];
    const size_t ray_count = frame.first_ray[members.back() + 1] - ray_base;
    // The span of rays can hold rays of samples of other clusters between the members':
    // those stay `kEnv` (no texel marked for them). Every other entry read is written
    // first, so hits and colors are only resized; the flags start at zero.
    ray_occluded.assign(ray_count, 0);
    ray_color.resize(ray_count);
    ray_hit.resize(ray_count);
    answer.assign(ray_count, kEnv);
    // Glossy hits in the last fade_fraction of the far distance fade to the environment.
    auto fade_at = [&](float t, vec3 dir, vec3 c_hit) {
      float w = std::clamp((far - t) / (options.fade_fraction * far), 0.0f, 1.0f);
      return w < 1.0f ? w * c_hit + (1.0f - w) * environment_radiance(scene.environment, dir) : c_hit;
    };
    auto fade = [&](const DepthImageHit& h, vec3 o, vec3 dir, vec3 c_hit) {
      return fade_at(glm::length(projection.unproject(h.pixel, h.depth) - o), dir, c_hit);
    };
    // The second layer (rays off the centre only) is needed by rays that went behind a
    // first-layer surface for good or found nothing.
    const bool layered = options.second_layer && (!k.planar || glossy);
    needs_second.assign(layered ? ray_count : 0, 0);
    second_t.assign(layered ? ray_count : 0, kInf);
    for_each_cluster_ray(frame, members, [&](uint32_t i, uint32_t r) {
      const vec3 o = frame.origin[i], dir = frame.direction[r];
      float t0 = 0.0f, t1 = 0.0f;
      std::optional<DepthImageHit> hit;
      const bool inside = clip_ray(k, o, dir, far, t0, t1);
      if (inside) hit = march_depth_image(projection, march_depth, o + t0 * dir, o + t1 * dir, march);
      if (layered && inside && (!hit || hit->filled)) needs_second[r - ray_base] = 1;
      if (hit) {
        ray_hit[r - ray_base] = *hit;
        answer[r - ray_base] = hit->filled ? kFill : kHit;
      } else {
        ray_color[r - ray_base] = environment_radiance(scene.environment, dir);
        answer[r - ray_base] = kEnv;
      }
    });
    clock.add_to(st.intersection_ms, st.intersection_cpu_ms);
    // Step 3b, shading: only the texels a hit's color lookup reads (most of an image is
    // never read), the same color each would get if all were shaded.
    clock.restart();
    mark_lookup_texels(images.depth, ray_hit, answer, kEnv, needed);
    st.shaded_texels += shade_texels(scene, frame.area_light_samples, cam, images, needed, color);
    st.texel_shading_ms += clock.wall_ms();
    clock.add_to(st.depth_images_ms, st.depth_images_cpu_ms);
    clock.restart();
    for_each_cluster_ray(frame, members, [&](uint32_t i, uint32_t r) {
      if (answer[r - ray_base] == kEnv) return;
      const DepthImageHit& hit = ray_hit[r - ray_base];
      const vec3 c_hit = lookup_color(color, images.depth, hit.pixel, hit.depth);
      ray_color[r - ray_base] = glossy ? fade(hit, frame.origin[i], frame.direction[r], c_hit) : c_hit;
    });
    clock.add_to(st.intersection_ms, st.intersection_cpu_ms);
    const bool two_layers = layered && std::find(needs_second.begin(), needs_second.end(), 1) != needs_second.end();
    if (two_layers) {
      // Step 3b for the second layer: the nearest front face behind the first layer, e.g.
      // the wall behind a fixture standing on a glossy floor.
      clock.restart();
      rs = rasterize_cluster_second_layer(draw_scene, k, draw, images, options.second_layer_separation, back);
      st.triangles_drawn += rs.triangles_submitted;
      st.second_layer_texels += uint64_t(cam.width) * uint64_t(cam.height);
      clock.add_to(st.depth_images_ms, st.depth_images_cpu_ms);
      // Those rays marched again in it (without fill); its texels are shaded on demand.
      clock.restart();
      ImageF back_block_min;
      const MarchOptions plain = block_march(back.depth, block, back_block_min);
      for_each_cluster_ray(frame, members, [&](uint32_t i, uint32_t r) {
        if (!needs_second[r - ray_base]) return;
        const vec3 o = frame.origin[i], dir = frame.direction[r];
        float t0 = 0.0f, t1 = 0.0f;
        clip_ray(k, o, dir, far, t0, t1);
        auto second = march_depth_image(projection, back.depth, o + t0 * dir, o + t1 * dir, plain);
        if (!second) return;
        const int x = std::clamp(int(second->pixel.x), 0, cam.width - 1);
        const int y = std::clamp(int(second->pixel.y), 0, cam.height - 1);
        const uint32_t t = back.triangle.at(x, y);
        if (t == kNoTriangle) return;
        const float u = back.barycentric.at(x, y, 0), v = back.barycentric.at(x, y, 1);
        vec3 c_hit = shade_reflected_point(scene, t, u, v, cam.position - triangle_point(scene, t, u, v),
                                           frame.area_light_samples);
        ray_color[r - ray_base] = glossy ? fade(*second, o, dir, c_hit) : c_hit;
        answer[r - ray_base] = kSecond;
        second_t[r - ray_base] = glm::length(projection.unproject(second->pixel, second->depth) - o);
      });
      clock.add_to(st.intersection_ms, st.intersection_cpu_ms);
    }
    // A curved cluster's own reflector, left out of its image: by default every ray is
    // intersected exactly with its triangles (own_exact); else an own layer (that reflector
    // alone, without the surface its rays start on) where every ray is marched again within
    // the reflector's bounds, up to its hit so far, and a hit there answers it (shaded on
    // demand).
    // Ray r's distance to its hit so far (first or second layer), at most t1.
    auto hit_so_far = [&](uint32_t r, vec3 o, float t1) {
      const uint8_t a = answer[r - ray_base];
      if (a == kHit) {
        const DepthImageHit& h = ray_hit[r - ray_base];
        return std::min(t1, glm::length(projection.unproject(h.pixel, h.depth) - o));
      }
      return a == kSecond ? std::min(t1, second_t[r - ray_base]) : t1;
    };
    const uint32_t own_object = clusters.reflector[c];
    const bool own_drawn = options.own_layer && !k.planar && own_object < scene.objects.size();
    bool own_holds = false;
    // The own layer at a finer resolution than the cluster image (the reflector's concave
    // parts span a few of its texels).
    ClusterCamera own_k = k;
    const int own_scale =
        std::max(1, std::min(options.own_layer_scale, options.own_layer_max_side / std::max(cam.width, cam.height)));
    own_k.camera.width = cam.width * own_scale;
    own_k.camera.height = cam.height * own_scale;
    const Camera& own_cam = own_k.camera;
    const CameraProjection own_projection(own_cam);
    const float own_separation = options.own_layer_separation * footprint[c] + epsilon;
    const bool own_exact = own_drawn && options.own_exact;
    if (own_exact) {
      // Every ray against its reflector's triangles, from its origin (as the reference
      // traces it) up to its hit so far; the nearest hit there answers it, shaded towards
      // the ray's origin.
      const double cpu0 = process_cpu_ms();
      clock.restart();
      if (!own_bvh[own_object]) {
        own_bvh[own_object].emplace(scene, own_object);
        st.own_exact_triangles += scene.objects[own_object].triangle_count;
      }
      clock.add_to(st.depth_images_ms, st.depth_images_cpu_ms);
      clock.restart();
      const ObjectBvh& bvh = *own_bvh[own_object];
      own_t.assign(ray_count, kInf);
      own_triangle.assign(ray_count, kNoTriangle);
      for_each_cluster_ray(frame, members, [&](uint32_t i, uint32_t r) {
        const vec3 o = frame.origin[i], dir = frame.direction[r];
        const auto hit = bvh.intersect(o, dir, 0.0f, hit_so_far(r, o, far));
        if (!hit) return;
        const vec3 c_hit = shade_reflected_point(scene, hit->triangle, hit->u, hit->v, -dir, frame.area_light_samples);
        ray_color[r - ray_base] = glossy ? fade_at(hit->t, dir, c_hit) : c_hit;
        answer[r - ray_base] = kOwn;
        own_t[r - ray_base] = hit->t;
        own_triangle[r - ray_base] = hit->triangle;
      });
      clock.add_to(st.intersection_ms, st.intersection_cpu_ms);
      st.own_exact_cpu_ms += process_cpu_ms() - cpu0;
    } else if (own_drawn) {
      clock.restart();
      const Object& obj = scene.objects[own_object];
      if (!options.cull || !cull_cluster_object(scene, own_blocks, own_k, own_object, cull_margin, own_runs))
        own_runs.assign(1, TriangleRun{obj.first_triangle, obj.triangle_count, obj.first_vertex, obj.vertex_count});
      const float focal_k = focal_length_px(own_cam), p = footprint[c];
      // The points' footprint in texels at their depth, one more for the texels between them.
      auto radius = [&](float depth) { return std::clamp(int(std::ceil(p * focal_k / depth)) + 1, 1, 8); };
      const ImageF start = start_depths(own_projection, own_cam.width, own_cam.height, members, frame.position, radius);
      ClusterDrawList own_draw;
      own_draw.culled = true;
      own_draw.triangles = own_runs;
      own_draw.object_bounds = object_bounds;
      own_draw.clip_margin = cull_margin;
      rs = rasterize_cluster_own_layer(scene, own_k, own_draw, start, own_separation, own);
      st.triangles_drawn += rs.triangles_submitted;
      st.own_layer_texels += uint64_t(own_cam.width) * uint64_t(own_cam.height);
      own_holds = std::find_if(own.triangle.data().begin(), own.triangle.data().end(),
                               [](uint32_t t) { return t != kNoTriangle; }) != own.triangle.data().end();
      if (own_holds && own_box[own_object].empty())
        for (uint32_t v = obj.first_vertex; v < obj.first_vertex + obj.vertex_count; ++v)
          own_box[own_object].extend(scene.positions[v]);
      clock.add_to(st.depth_images_ms, st.depth_images_cpu_ms);
    }
    if (own_holds) {
      clock.restart();
      ImageF own_block_min;
      const MarchOptions plain = block_march(own.depth, block, own_block_min);
      const Bounds3& box = own_box[own_object];
      for_each_cluster_ray(frame, members, [&](uint32_t i, uint32_t r) {
        const vec3 o = frame.origin[i], dir = frame.direction[r];
        float t0 = 0.0f, t1 = 0.0f;
        if (!clip_ray(k, o, dir, far, t0, t1)) return;
        t1 = hit_so_far(r, o, t1);
        // Past its own start surface: where the ray has risen `separation` above the
        // sample's tangent plane (a hit before that is the surface it starts on).
        t0 = std::max(t0, own_separation / std::max(glm::dot(dir, frame.normal[i]), 0.05f));
        if (!clip_to_box(box, o, dir, t0, t1)) return;
        auto hit = march_depth_image(own_projection, own.depth, o + t0 * dir, o + t1 * dir, plain);
        if (!hit) return;
        const int x = std::clamp(int(hit->pixel.x), 0, own_cam.width - 1);
        const int y = std::clamp(int(hit->pixel.y), 0, own_cam.height - 1);
        const uint32_t t = own.triangle.at(x, y);
        // A ray meets a surface from its front; a "hit" on a back face is the ray passing
        // behind a silhouette of the reflector.
        if (t == kNoTriangle || !(glm::dot(dir, triangle_normal(scene, t)) < 0.0f)) return;
        const float u = own.barycentric.at(x, y, 0), v = own.barycentric.at(x, y, 1);
        const vec3 c_hit = shade_reflected_point(scene, t, u, v, cam.position - triangle_point(scene, t, u, v),
                                                 frame.area_light_samples);
        const float t_hit = glm::length(own_projection.unproject(hit->pixel, hit->depth) - o);
        ray_color[r - ray_base] = glossy ? fade_at(t_hit, dir, c_hit) : c_hit;
        answer[r - ray_base] = kOwn;
      });
      clock.add_to(st.intersection_ms, st.intersection_cpu_ms);
    }
    // Step 3d: G = the mean over each sample's rays.
    clock.restart();
    for (uint32_t i : members) {
      vec3 sum(0.0f);
      for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r) {
        sum += ray_color[r - ray_base];
        const uint8_t a = answer[r - ray_base];
        out.flags[i] |= a == kFill ? kBehindFill : a == kEnv ? kEnvFallback : a == kSecond ? kSecondLayer : a == kOwn ? kOwnLayer : 0;
        st.second_layer_rays += a == kSecond;
        st.own_layer_rays += a == kOwn;
      }
      out.radiance[i] = sum / float(frame.first_ray[i + 1] - frame.first_ray[i]);
    }
    clock.add_to(st.intersection_ms, st.intersection_cpu_ms);
    // Occlusion errors, a diagnostic outside the timed steps: the surface Embree hits is
    // not what the image holds there.
    auto held_in_own = [&](vec3 x, uint32_t tri) {
      const auto p = own_projection(x);
      return p && held_near(own, p->pixel, p->depth, tri);
    };
    // An exact own-reflector hit is right when it is the reference's triangle or point.
    auto own_hit_right = [&](uint32_t r, uint32_t tri) {
      const float t = reference->hit_t[r];
      return own_exact && answer[r - ray_base] == kOwn &&
             (own_triangle[r - ray_base] == tri || std::abs(own_t[r - ray_base] - t) <= 0.01f * t);
    };
    if (reference) {
      for_each_cluster_ray(frame, members, [&](uint32_t i, uint32_t r) {
        if (reference->hit_triangle[r] == kNoTriangle) return;
        const vec3 o = frame.origin[i], dir = frame.direction[r];
        const vec3 x = o + reference->hit_t[r] * dir;
        const uint32_t tri = reference->hit_triangle[r];
        auto pr = projection(x);
        OcclusionCause cause = OcclusionCause::None;
        if (reference->hit_t[r] > far)
          cause = OcclusionCause::None;  // beyond the (glossy) far distance: faded out by design
        else if (own_hit_right(r, tri))
          cause = OcclusionCause::None;  // the exact own-reflector test answered it with that surface
        else if (glm::dot(x - k.plane_point, k.plane_normal) <= k.clip_offset)
          cause = OcclusionCause::BehindNear;
        else if (!pr || pr->pixel.x < 0.0f || pr->pixel.y < 0.0f || pr->pixel.x >= float(cam.width) ||
                 pr->pixel.y >= float(cam.height))
          cause = OcclusionCause::OutsideImage;
        else if (!k.planar && scene.triangle_object[tri] == own_object &&
                 !(own_drawn && !own_exact && held_in_own(x, tri)))
          cause = OcclusionCause::OwnReflector;
        else if (!visible_near(images, pr->pixel, pr->depth, tri) &&
                 !(two_layers && visible_near(back, pr->pixel, pr->depth, tri)))
          // Hidden only if no texel within one of its projection holds the surface or
          // something at its depth or beyond (resolution is not occlusion), in either layer.
          cause = OcclusionCause::Hidden;
        if (cause != OcclusionCause::None) {
          out.flags[i] |= kOcclusionError;
          ray_occluded[r - ray_base] = 1;
          if (out.occlusion_cause[i] == uint8_t(OcclusionCause::None)) out.occlusion_cause[i] = uint8_t(cause);
        }
      });
    }
    for (uint32_t i : members) {
      st.rays += frame.first_ray[i + 1] - frame.first_ray[i];
      for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r) {
        st.occlusion_error_rays += ray_occluded[r - ray_base];
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (glossy_lobe_half_angle(frame.gloss[i]) > 0.0f) continue;
    ++st.mirror_samples;
    st.mirror_occlusion_error_samples += (out.flags[i] & kOcclusionError) != 0;
  }
  for (uint8_t cause : out.occlusion_cause)
    if (cause != uint8_t(OcclusionCause::None)) ++st.occlusion_cause_samples[cause];
  for (uint8_t flag : out.flags) {
    st.env_fallback_samples += (flag & kEnvFallback) != 0;
    st.occlusion_error_samples += (flag & kOcclusionError) != 0;
    st.behind_fill_samples += (flag & kBehindFill) != 0;
  }
  return out;
}

}  // namespace proxima
