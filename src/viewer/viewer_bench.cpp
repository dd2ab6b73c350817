#include "proxima/viewer/viewer_bench.h"

#include <algorithm>
#include <cstdio>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
#include "proxima/core/timer.h"
#include "proxima/viewer/viewer_session.h"

namespace proxima {

namespace {

double fps(double ms) { return ms > 0.0 ? 1000.0 / ms : 0.0; }

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

// Indices of the techniques to time: the named ones, or every available one.
std::vector<int> chosen_techniques(const ViewerSession& session, const std::vector<std::string>& names) {
  std::vector<int> chosen;
  for (size_t i = 0; i < session.techniques().size(); ++i) {
    const Technique& t = session.techniques()[i];
    const bool wanted = names.empty() || std::find(names.begin(), names.end(), t.name) != names.end();
    if (wanted && t.unavailable.empty()) chosen.push_back(int(i));
  }
  for (const std::string& n : names) {
    bool found = false;
    for (int i : chosen) found = found || session.techniques()[size_t(i)].name == n;
    if (!found) fail_input("--techniques: '" + n + "' is not an available technique here");
  }
  return chosen;
}

// One technique's figures.
struct TechniqueTimes {
  std::vector<double> moving, refine;
  double first = 0.0, error = -1.0;
  int render_width = 0, render_height = 0;
  std::vector<StepTime> steps;
};

constexpr float kFrameSeconds = 1.0f / 30.0f;

// Each technique's one-off builds (cube map, occluders) in its first frame; a build
// announced by a placeholder frame (GIBR) runs in the next one.
void warm_up(ViewerSession& session, int technique, TechniqueTimes& t) {
  session.select_technique(technique);
  move(session, 0);
  session.frame(kFrameSeconds);
  t.first = session.status().frame_ms;
  for (int i = 0; i < 2 && session.status().pending; ++i) {
    session.frame(kFrameSeconds);
    t.first += session.status().frame_ms;
  }
  release(session);
  if (session.status().pending)
    fail_input("--techniques: " + session.techniques()[size_t(technique)].name + ": " + session.status().note);
}

// One block: `frames` moving frames, then the still refine frame (and the error once).
void time_block(ViewerSession& session, const ViewerBenchOptions& o, int round, TechniqueTimes& t) {
  for (int i = 0; i < o.frames; ++i) {
    move(session, round * o.frames + i);
    session.frame(kFrameSeconds);
    t.moving.push_back(session.status().frame_ms);
  }
  t.render_width = session.status().render_width;
  t.render_height = session.status().render_height;
  t.steps = session.status().steps;
  release(session);
  session.frame(kFrameSeconds);  // still: the full-resolution frame
  t.refine.push_back(session.status().frame_ms);
  if (o.error && round == 0) {
    while (session.status().error_mae < 0.0) session.frame(kFrameSeconds);
    t.error = session.status().error_mae;
  }
}

std::string steps_text(const std::vector<StepTime>& steps) {
  std::string text;
  for (const StepTime& s : steps) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s%s %.1f", text.empty() ? "" : "; ", s.name.c_str(), s.ms);
    text += buf;
  }
  return text;
}

}  // namespace

void validate(const ViewerBenchOptions& o) {
  require_in_range(o.width, 16, 8192, "--width");
  require_in_range(o.height, 16, 8192, "--height");
  require_in_range(o.move_scale, 0, 16, "--move-scale", "(0 = adaptive)");
  require_in_range(o.frames, 1, 10000, "--frames");
  require_in_range(o.rounds, 1, 100, "--rounds");
}

Results run_viewer_bench(const Scene& scene, const ViewerBenchOptions& o, const study::StudyOutput& /*out*/,
                         Progress* /*progress*/) {
  validate(o);
  ViewerOptions vo;
  vo.move_scale = o.move_scale;
  vo.techniques.seed = o.seed;
  vo.speed = std::max(0.1f, 0.1f * scene_bounds(scene).diagonal());
  ViewerSession session(scene, pick_camera(scene, o.camera, o.width, o.height), o.width, o.height, vo);
  const std::vector<int> chosen = chosen_techniques(session, o.techniques);
  std::vector<TechniqueTimes> times(chosen.size());
  for (size_t k = 0; k < chosen.size(); ++k) warm_up(session, chosen[k], times[k]);
  for (int r = 0; r < o.rounds; ++r)
    for (size_t k = 0; k < chosen.size(); ++k) {
      session.select_technique(chosen[k]);
      time_block(session, o, r, times[k]);
    }

  Results results;
  Table table{"Viewer frame rate while moving, " + scene.name + ", window " + std::to_string(o.width) + "x" +
                  std::to_string(o.height) + ", " + std::to_string(active_threads()) + " threads",
              {"technique", "rendered_while_moving", "moving_ms_median", "moving_fps", "refine_ms_median",
               "refine_fps", "first_frame_ms", "error_mae_still", "steps_last_moving_frame"},
              {}};
  for (size_t k = 0; k < chosen.size(); ++k) {
    const TechniqueTimes& t = times[k];
    const std::string name = session.techniques()[size_t(chosen[k])].name;
    const double ms = median(t.moving), full = median(t.refine);
    table.rows.push_back({name, std::to_string(t.render_width) + "x" + std::to_string(t.render_height), ms, fps(ms),
                          full, fps(full), t.first, t.error, steps_text(t.steps)});
    results.metrics[name + "_moving_ms"] = ms;
    results.metrics[name + "_moving_fps"] = fps(ms);
    results.metrics[name + "_refine_ms"] = full;
    results.metrics[name + "_first_frame_ms"] = t.first;
    results.metrics[name + "_render_width"] = t.render_width;
    results.metrics[name + "_render_height"] = t.render_height;
    if (o.error) results.metrics[name + "_error_mae"] = t.error;
  }
  results.tables.push_back(table);
  return results;
}

}  // namespace proxima
