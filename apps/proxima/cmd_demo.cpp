// `proxima demo`: the main job on built-in scenes. For now: reference renders of `cornell`
// and `living-room` into --out; techniques add their sections as they land (issue 11).
#include <cstdio>

#include "command.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/scene/load.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::cli {

Command register_demo(CLI::App& root) {
  static CommonOptions f;
  auto* app = root.add_subcommand("demo", "run the main job on the built-in scenes");
  add_size_flags(app, f);
  add_threads_flag(app, f);
  add_seed_flag(app, f);
  add_out_flag(app, f, false);
  f.out = "out/demo";
  return {app, [] {
            ThreadLimit limit(f.threads);
            auto out = prepare_out_dir(f.out);
            Results results;
            results.command = command_line();
            results.threads = active_threads();
            Table table{"reference renders", {"scene", "triangles", "width", "height", "bvh_build_ms", "render_ms"}, {}};
            for (const char* name : {"cornell", "living-room"}) {
              Scene scene = load_scene(name);
              Camera cam = pick_camera(scene, {}, f.width, f.height);
              RayScene rays(scene);
              ReferenceOptions opts;
              opts.seed = f.seed;
              opts.supersample = 2;
              Stopwatch w;
              ImageF color = render_reference(scene, rays, cam, opts);
              double ms = w.elapsed_ms();
              std::string file = std::string(name) + "_reference.png";
              write_png_linear(out / file, color);
              results.images[std::string(name) + "_reference"] = file;
              results.metrics[std::string(name) == "cornell" ? "cornell_render_ms" : "living_room_render_ms"] = ms;
              table.rows.push_back({std::string(name), double(scene.triangles.size()), double(cam.width),
                                    double(cam.height), rays.build_ms(), ms});
              std::fprintf(stderr, "demo: %s rendered in %.0f ms → %s\n", name, ms, (out / file).c_str());
            }
            results.tables.push_back(table);
            publish_results(out, results);
            return 0;
          }};
}

}  // namespace proxima::cli
