// `proxima render`: the reference (ray-traced) image of a scene plus its EXR buffers.
#include <cmath>
#include <cstdio>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/scene/load.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::cli {

namespace {

struct RenderFlags {
  CommonOptions common;
  CameraChoice camera;
  ReferenceOptions reference;
  float time = -1.0f;  // pose time for animated scenes; −1 = the path frame's time or 0
};

// Triangle ids as float for EXR (exact up to 2^24; −1 where nothing was hit).
ImageF ids_as_float(const ImageU32& ids) {
  ImageF out(ids.width(), ids.height(), 1);
  for (size_t i = 0; i < ids.data().size(); ++i)
    out.data()[i] = ids.data()[i] == kNoTriangle ? -1.0f : float(ids.data()[i]);
  return out;
}

}  // namespace

Command register_render(CLI::App& root) {
  static RenderFlags f;
  auto* app = root.add_subcommand("render", "render the ray-traced reference image of a scene");
  add_scene_flag(app, f.common, "cornell");
  add_camera_flags(app, f.camera);
  add_size_flags(app, f.common);
  add_threads_flag(app, f.common);
  add_seed_flag(app, f.common);
  add_out_flag(app, f.common, true);
  app->add_option("--spp", f.reference.supersample, "supersampling: K×K stratified samples per pixel")
      ->capture_default_str();
  app->add_option("--light-samples", f.reference.area_light_samples, "N×N samples per area light")
      ->capture_default_str();
  app->add_option("--glossy-rays", f.reference.glossy_rays, "rays per glossy lobe")->capture_default_str();
  app->add_option("--bounces", f.reference.max_bounces, "reflection depth (0 = none)")->capture_default_str();
  app->add_option("--time", f.time, "pose time in seconds for animated scenes");

  return {app, [] {
            const ReferenceOptions& r = f.reference;
            if (r.supersample < 1 || r.supersample > 64) fail_input("--spp: must be in 1..64");
            if (r.area_light_samples < 1 || r.area_light_samples > 64) fail_input("--light-samples: must be in 1..64");
            if (r.glossy_rays < 1 || r.glossy_rays > 4096) fail_input("--glossy-rays: must be in 1..4096");
            if (r.max_bounces < 0 || r.max_bounces > 16) fail_input("--bounces: must be in 0..16");
            if (f.common.threads < 0) fail_input("--threads: must be ≥ 0");
            ThreadLimit limit(f.common.threads);
            Scene scene = load_scene(f.common.scene);
            Camera camera = pick_camera(scene, f.camera, f.common.width, f.common.height);
            auto out = prepare_out_dir(f.common.out);

            float t = f.time >= 0.0f ? f.time : 0.0f;
            if (f.time < 0.0f && !f.camera.path.empty()) {
              // Animated objects move with the path's clock.
              for (const auto& p : scene.camera_paths)
                if (p.name == f.camera.path) t = frame_time(p, f.camera.frame);
            }
            if (has_animation(scene)) scene = pose_scene(scene, t);

            ReferenceOptions opts = r;
            opts.seed = f.common.seed;
            Results results;
            results.command = command_line();
            results.threads = active_threads();
            Stopwatch watch;
            RayScene rays(scene);
            results.metrics["bvh_build_ms"] = rays.build_ms();
            watch.restart();
            ItemBuffer item = trace_item_buffer(scene, rays, camera);
            results.metrics["item_buffer_ms"] = watch.elapsed_ms();
            watch.restart();
            ImageF color = render_reference(scene, rays, camera, opts);
            results.metrics["render_ms"] = watch.elapsed_ms();

            write_png_linear(out / "color.png", color);
            write_exr(out / "color.exr", color);
            write_exr(out / "depth.exr", item.depth);
            write_exr(out / "normal.exr", item.normal);
            write_exr(out / "id.exr", ids_as_float(item.triangle));
            results.images = {{"color", "color.png"}, {"color_linear", "color.exr"}, {"depth", "depth.exr"},
                              {"normal", "normal.exr"}, {"triangle_id", "id.exr"}};
            size_t hit = 0;
            for (uint32_t id : item.triangle.data()) hit += id != kNoTriangle;
            results.metrics["coverage_pct"] = 100.0 * double(hit) / double(item.triangle.pixel_count());
            results.tables.push_back({"render " + scene.name,
                                      {"triangles", "width", "height", "spp", "bvh_build_ms", "render_ms"},
                                      {{double(scene.triangles.size()), double(camera.width), double(camera.height),
                                        double(opts.supersample * opts.supersample), results.metrics["bvh_build_ms"],
                                        results.metrics["render_ms"]}}});
            publish_results(out, results);
            return 0;
          }};
}

}  // namespace proxima::cli
