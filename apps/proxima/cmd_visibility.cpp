// `proxima visibility`: exact visibility maps along a camera path, checked against Embree
// (study/visibility.h, docs/visibility.md).
#include <cstdio>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/scene/visibility_models.h"
#include "proxima/study/visibility.h"
#include "scene_study.h"

namespace proxima::cli {

namespace {

// Exit code of `--strict` when at least one map failed its self-check (results are written).
constexpr int kExitSelfCheck = 3;

struct VisibilityFlags {
  CommonOptions common;
  study::VisibilityOptions options;
  int floors = 0;       // building only; 0 = the default 5
  bool strict = false;  // exit kExitSelfCheck when a map fails its self-check
};

void add_scene_flags(CLI::App* app, VisibilityFlags& f) {
  f.common.width = f.options.width;
  f.common.height = f.options.height;
  add_common_flags(app, f.common, {.scene = "rooms", .seed = false});
  app->add_option("--path", f.options.path, "camera path, by index or name (default: the first)");
  app->add_option("--floors", f.floors, "floors of the `building` scene (default 5)");
  app->add_option("--frames", f.options.frames, "viewpoints: the first N frames of the path (default: all)");
}

void add_map_flags(CLI::App* app, VisibilityFlags& f) {
  study::VisibilityOptions& o = f.options;
  app->add_flag("!--no-oracle", o.oracle, "skip the Embree comparison");
  app->add_flag("!--no-images", o.images, "skip the per-viewpoint SVG and PNG");
  app->add_option("--load", o.load, "winged-pair file to use instead of building one");
  app->add_option("--save", o.save, "write the winged pair built to this file");
  app->add_option("--selfcheck-rays", o.selfcheck_rays, "Embree rays of each map's self-check (default 128)");
  app->add_flag("--strict", f.strict, "exit 3 when any map fails its self-check (results are still written)");
}

int run(VisibilityFlags& f) {
  if (f.floors != 0 && f.common.scene != "building") fail_input("--floors: only the `building` scene has floors");
  set_common_options(f.common, f.options);
  StudyRunOptions how{.log_progress = false};  // a bar on a terminal; logs and pipes get none
  if (f.floors != 0) how.scene = [&f] { return make_vis_building(f.floors); };
  SceneStudyRun run = run_scene_study(f.common, f.options, study::run_visibility, how);
  const int failed = int(run.results.metrics.at("maps_failed_selfcheck"));
  const int maps = int(run.results.metrics.at("viewpoints"));
  const std::string scene = run.scene;
  publish_study(std::move(run));
  if (failed > 0)
    std::fprintf(stderr, "warning: %s: %d of %d visibility maps failed their self-check%s\n", scene.c_str(),
                 failed, maps, f.strict ? "" : " (--strict makes this exit 3)");
  return f.strict && failed > 0 ? kExitSelfCheck : 0;
}

}  // namespace

Command register_visibility(CLI::App& root) {
  static VisibilityFlags f;
  auto* app = root.add_subcommand("visibility", "exact visibility maps by beam tracing a BSP cell complex, vs Embree");
  add_scene_flags(app, f);
  add_map_flags(app, f);
  return {app, [] { return run(f); }};
}

}  // namespace proxima::cli
