// `proxima bench view` (issue 12): frame rate of every viewer technique while the camera
// moves, headless (ViewerSession without a window, overlay drawn as on screen), plus the
// full-resolution refine frame and optionally the error vs the reference once still.
#include <algorithm>
#include <cstdio>

#include "command.h"
#include "frame_series.h"
#include "view_flags.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/scene/load.h"
#include "proxima/viewer/viewer_session.h"

namespace proxima::cli {

namespace {

struct BenchViewFlags {
  ViewSetup setup;
  std::string out = "out/bench-view";
  int frames = 10;  // moving frames per block
  int rounds = 3;   // blocks per technique, round-robin over the techniques
  bool error = false;
  std::vector<std::string> techniques;
};

// Frame i of a block: fly forward for 10 frames, back for 10, turning right all along,
// so long runs stay in the room.
void move(ViewerSession& s, int i) {
  const bool forward = (i / 10) % 2 == 0;
  s.key_down(forward ? "w" : "s");
  s.mouse_motion(vec2(3.0f, 0.0f));
}

void release(ViewerSession& s) {
  s.key_up("w");
  s.key_up("s");
}

int run_bench_view(const BenchViewFlags& f) {
  validate_view_flags(f.setup);
  if (f.frames < 1 || f.frames > 10000) fail_input("--frames: must be in 1..10000");
  if (f.rounds < 1 || f.rounds > 100) fail_input("--rounds: must be in 1..100");
  ThreadLimit limit(f.setup.common.threads);
  const std::unique_ptr<ViewerSession> owned = make_view_session(f.setup, {});
  ViewerSession& session = *owned;
  const auto out = prepare_out_dir(f.out);
  const std::string name = session.scene().name;

  std::vector<int> chosen;
  for (size_t i = 0; i < session.techniques().size(); ++i) {
    const Technique& t = session.techniques()[i];
    const bool wanted = f.techniques.empty() ||
                        std::find(f.techniques.begin(), f.techniques.end(), t.name) != f.techniques.end();
    if (wanted && t.unavailable.empty()) chosen.push_back(int(i));
  }
  for (const std::string& n : f.techniques) {
    bool found = false;
    for (int i : chosen) found = found || session.techniques()[size_t(i)].name == n;
    if (!found) fail_input("--techniques: '" + n + "' is not an available technique here");
  }
  const float dt = 1.0f / 30.0f;
  const size_t n = chosen.size();
  std::vector<std::vector<double>> moving(n), refine(n);
  std::vector<double> first(n, 0.0), error(n, -1.0);
  std::vector<int> rw(n), rh(n);
  std::vector<std::vector<StepTime>> steps(n);
  // Warm-up: each technique's one-off builds (cube map, occluders) in its first frame; a
  // build announced by a placeholder frame (GIBR) runs in the next one.
  for (size_t k = 0; k < n; ++k) {
    session.select_technique(chosen[k]);
    move(session, 0);
    session.frame(dt);
    first[k] = session.status().frame_ms;
    for (int i = 0; i < 2 && session.status().pending; ++i) {
      session.frame(dt);
      first[k] += session.status().frame_ms;
    }
    release(session);
    if (session.status().pending)
      fail_input("--techniques: " + session.techniques()[size_t(chosen[k])].name + ": " + session.status().note);
  }
  for (int r = 0; r < f.rounds; ++r)
    for (size_t k = 0; k < n; ++k) {
      session.select_technique(chosen[k]);
      for (int i = 0; i < f.frames; ++i) {
        move(session, r * f.frames + i);
        session.frame(dt);
        moving[k].push_back(session.status().frame_ms);
      }
      rw[k] = session.status().render_width;
      rh[k] = session.status().render_height;
      steps[k] = session.status().steps;
      release(session);
      session.frame(dt);  // still: the full-resolution frame
      refine[k].push_back(session.status().frame_ms);
      if (f.error && r == 0) {
        while (session.status().error_mae < 0.0) session.frame(dt);
        error[k] = session.status().error_mae;
      }
    }

  Results results;
  results.command = command_line();
  results.threads = active_threads();
  Table table{"Viewer frame rate while moving, " + name + ", window " + std::to_string(f.setup.common.width) + "x" +
                  std::to_string(f.setup.common.height) + ", " + std::to_string(active_threads()) + " threads",
              {"technique", "rendered_while_moving", "moving_ms_median", "moving_fps", "refine_ms_median",
               "refine_fps", "first_frame_ms", "error_mae_still", "steps_last_moving_frame"},
              {}};
  for (size_t k = 0; k < n; ++k) {
    const std::string t = session.techniques()[size_t(chosen[k])].name;
    const double ms = median(moving[k]), full = median(refine[k]);
    std::string step_text;
    for (const StepTime& s : steps[k]) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s%s %.1f", step_text.empty() ? "" : "; ", s.name.c_str(), s.ms);
      step_text += buf;
    }
    table.rows.push_back({t, std::to_string(rw[k]) + "x" + std::to_string(rh[k]), ms, fps(ms), full, fps(full),
                          first[k], error[k], step_text});
    results.metrics[t + "_moving_ms"] = ms;
    results.metrics[t + "_moving_fps"] = fps(ms);
    results.metrics[t + "_refine_ms"] = full;
    results.metrics[t + "_first_frame_ms"] = first[k];
    results.metrics[t + "_render_width"] = rw[k];
    results.metrics[t + "_render_height"] = rh[k];
    if (f.error) results.metrics[t + "_error_mae"] = error[k];
  }
  results.tables.push_back(table);
  publish_results(out, results);
  return 0;
}

}  // namespace

Command register_bench_view(CLI::App& bench) {
  static BenchViewFlags f;
  auto* app = bench.add_subcommand("view", "viewer techniques: frames/s while moving (headless), refine frame, "
                                           "error vs the reference");
  f.setup.move_scale = 2;
  add_view_flags(app, f.setup, "render at 1/N of the window per side while moving (0 = adaptive)");
  app->add_option("--out", f.out, "output directory (created if missing)")->capture_default_str();
  app->add_option("--frames", f.frames, "moving frames per block")->capture_default_str();
  app->add_option("--rounds", f.rounds, "blocks per technique, round-robin")->capture_default_str();
  app->add_option("--techniques", f.techniques, "comma-separated subset (default: every available one)")
      ->delimiter(',');
  app->add_flag("--error", f.error, "also wait for each technique's reference once still: its MAE (slow)");
  return {app, [] { return run_bench_view(f); }};
}

}  // namespace proxima::cli
