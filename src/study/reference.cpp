#include "proxima/study/reference.h"

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/range_check.h"
#include "proxima/core/timer.h"
#include "proxima/scene/camera_path.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::study {

namespace {

// The pose time: --time, else the --path frame's time (animated objects move with the
// path's clock), else 0.
float pose_time(const Scene& scene, const ReferenceStudyOptions& o) {
  if (o.time >= 0.0f) return o.time;
  float t = 0.0f;
  if (!o.camera.path.empty())
    for (const auto& p : scene.camera_paths)
      if (p.name == o.camera.path) t = frame_time(p, o.camera.frame);
  return t;
}

}  // namespace

void validate(const ReferenceStudyOptions& o) {
  require_in_range(o.supersample, 1, 64, "--spp");
  require_in_range(o.light_samples, 1, 64, "--light-samples");
  require_in_range(o.glossy_rays, 1, 4096, "--glossy-rays");
  require_in_range(o.bounces, 0, 16, "--bounces");
}

ReferenceOptions reference_options(const ReferenceStudyOptions& o) {
  ReferenceOptions r;
  r.supersample = o.supersample;
  r.area_light_samples = o.light_samples;
  r.glossy_rays = o.glossy_rays;
  r.max_bounces = o.bounces;
  r.seed = o.seed;
  return r;
}

ReferenceRender render_reference_view(const Scene& rest, const ReferenceStudyOptions& options, bool item_buffer) {
  validate(options);
  ReferenceRender r;
  r.camera = pick_camera(rest, options.camera, options.width, options.height);
  const Scene posed = has_animation(rest) ? pose_scene(rest, pose_time(rest, options)) : Scene{};
  const Scene& scene = has_animation(rest) ? posed : rest;
  r.triangles = scene.triangles.size();
  const RayScene rays(scene);
  r.bvh_build_ms = rays.build_ms();
  Stopwatch watch;
  if (item_buffer) r.item = trace_item_buffer(scene, rays, r.camera);
  r.item_buffer_ms = watch.elapsed_ms();
  watch.restart();
  r.color = render_reference(scene, rays, r.camera, reference_options(options));
  r.render_ms = watch.elapsed_ms();
  return r;
}

Results run_reference(const Scene& scene, const ReferenceStudyOptions& options, const StudyOutput& out,
                      Progress* /*progress*/) {
  const ReferenceRender r = render_reference_view(scene, options, true);
  Results results;
  results.metrics["bvh_build_ms"] = r.bvh_build_ms;
  results.metrics["item_buffer_ms"] = r.item_buffer_ms;
  results.metrics["render_ms"] = r.render_ms;
  write_image(out, results, "color", "color.png", r.color);
  write_exr_image(out, results, "color_linear", "color.exr", r.color);
  write_exr_image(out, results, "depth", "depth.exr", r.item.depth);
  write_exr_image(out, results, "normal", "normal.exr", r.item.normal);
  write_exr_image(out, results, "triangle_id", "id.exr", triangle_ids_as_float(r.item.triangle));
  size_t hit = 0;
  for (uint32_t id : r.item.triangle.data()) hit += id != kNoTriangle;
  results.metrics["coverage_pct"] = 100.0 * double(hit) / double(r.item.triangle.pixel_count());
  results.tables.push_back({"render " + scene.name,
                            {"triangles", "width", "height", "spp", "bvh_build_ms", "render_ms"},
                            {{double(r.triangles), double(r.camera.width), double(r.camera.height),
                              double(options.supersample * options.supersample), r.bvh_build_ms, r.render_ms}}});
  return results;
}

}  // namespace proxima::study
