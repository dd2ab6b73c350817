// Demo section: temporal reuse of reflections with reflection depth images (thesis ch. 5;
// `proxima reflect --method temporal`, docs/temporal.md).
#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "demo.h"
#include "proxima/eval/image_error.h"
#include "proxima/scene/load.h"
#include "proxima/study/temporal_reflect.h"

namespace proxima::cli::demo {

namespace {

struct Run {
  const char* scene;
  const char* path;
  const char* thesis_speedup;  // Table 22, fps ratio vs full ray tracing
};
constexpr Run kRuns[] = {{"bathroom", "walk", "1.8–1.9×"}, {"living-room", "walk", "3.6–3.7×"}};

struct Settings {
  int size, frames;
};
Settings settings(const Context& c) { return c.full ? Settings{512, 500} : Settings{128, 60}; }

Section intro(const Settings& s) {
  return {"temporal", "Temporal reuse of reflections (thesis ch. 5)",
          "A key frame's reflection depth image (normal, depth, reflected radiance and reflection "
          "distance per pixel) is reused by later frames: a best-match search finds, per reflective "
          "pixel, where the key frame saw the same reflected point; the key frame's grid is warped by "
          "those offsets and reprojected; pixels the warp cannot supply (disoccluded, stretched) "
          "and those whose blend of key samples is likely visibly wrong (expected display error above 8 "
          "levels, --blend-error) are traced again with Embree. A new key frame starts when more than 30% of the reflective pixels "
          "were recomputed, or once a reuse frame's work (recomputed rays plus the fixed steps) reaches the "
          "average work per frame since the key frame (--keyframe-cost). Compared with full ray tracing of every frame and with direct depth "
          "reprojection, which treats reflections as if they were painted on the surface. "
          "docs/temporal.md.\n\n"
          "This run: " + std::to_string(s.size) + "² frames, the first " + std::to_string(s.frames) +
              " frames of each path, 8 lobe rays on glossy surfaces. The thesis ran 500 frames at "
              "1024² on a GPU (MAE 0.13–0.45, 18–21% recomputed).",
          {}, {}, {}};
}

// One path through the study, with the command line that reproduces it.
ChildRun run_path(Context& c, const Run& run_def, const Settings& s) {
  const std::vector<std::string> args = {"reflect", "--method", "temporal", "--scene", run_def.scene, "--path",
                                         run_def.path, "--frames", std::to_string(s.frames), "--width",
                                         std::to_string(s.size), "--height", std::to_string(s.size),
                                         "--glossy-rays", "8", "--compare", "--seed", std::to_string(c.seed)};
  study::TemporalReflectOptions o;
  o.path = run_def.path;
  o.frames = s.frames;
  o.width = o.height = s.size;
  o.glossy_rays = 8;
  o.compare = true;
  o.seed = c.seed;
  const Scene scene = load_scene(run_def.scene);
  return run_study(c, std::string("temporal/") + run_def.scene + "-" + run_def.path, args,
                   [&](const study::StudyOutput& out) { return study::run_temporal_reflect(scene, o, out); });
}

// The recompute fraction per frame, from the study's per-frame table.
std::vector<double> recompute_series(const Results& r) {
  std::vector<double> series;
  for (const Table& t : r.tables) {
    if (t.title != "Per frame") continue;
    size_t col = 0;
    while (col < t.columns.size() && t.columns[col] != "recompute_pct") ++col;
    for (const auto& row : t.rows)
      if (col < row.size() && std::holds_alternative<double>(row[col])) series.push_back(std::get<double>(row[col]));
  }
  return series;
}

void add_images(Context& c, Section& section, const ChildRun& run, const std::string& where) {
  const ImageF temporal = read_child_image(c, run.dir + "/temporal.png");
  const ImageF direct = read_child_image(c, run.dir + "/direct.png");
  const ImageF reference = read_child_image(c, run.dir + "/reference.png");
  add_image(c, section, where + ": full ray tracing", run.dir + "/reference.png");
  add_image(c, section, where + ": temporal reuse", run.dir + "/temporal.png");
  add_image(c, section, where + ": direct reprojection", run.dir + "/direct.png");
  add_image(c, section, where + ": recomputed pixels (red disoccluded, orange unreliable)",
            run.dir + "/recompute.png");
  write_image(c, section, where + ": error of temporal reuse", run.dir + "/heat_temporal.png",
              error_heatmap(error_image(temporal, reference), kErrorHeatmapMax));
  write_image(c, section, where + ": error of direct reprojection", run.dir + "/heat_direct.png",
              error_heatmap(error_image(direct, reference), kErrorHeatmapMax));
  add_heatmap_legend(c, section, kErrorHeatmapMax);
}

// Frames as rows, one column per path (NaN past a path's end).
Table per_frame_table(const std::vector<std::string>& paths, const std::vector<std::vector<double>>& series) {
  Table t{"Recomputed share of the reflective pixels per frame (temporal reuse)", {"frame"}, {}};
  t.columns.insert(t.columns.end(), paths.begin(), paths.end());
  size_t frames = 0;
  for (const auto& one : series) frames = std::max(frames, one.size());
  for (size_t f = 0; f < frames; ++f) {
    std::vector<std::variant<std::string, double>> row{double(f)};
    for (const auto& one : series) row.push_back(f < one.size() ? one[f] : std::nan(""));
    t.rows.push_back(row);
  }
  return t;
}

}  // namespace

int temporal_steps(const Context&) { return int(std::size(kRuns)); }

void temporal_section(Context& c) {
  const Settings s = settings(c);
  Section section = intro(s);
  Table quality{"Temporal reuse vs direct reprojection vs full ray tracing (thesis: MAE 0.13–0.45, 18–21% recomputed)",
                {"scene / path", "temporal MAE", "direct reprojection MAE", "recomputed %", "key-frame interval avg",
                 "reflection speed-up vs ray tracing", "frame speed-up", "thesis speed-up (Table 22)"},
                {}};
  std::vector<std::string> paths;
  std::vector<std::vector<double>> series;
  for (const Run& run_def : kRuns) {
    const std::string where = std::string(run_def.scene) + " / " + run_def.path;
    const ChildRun run = run_path(c, run_def, s);
    section.commands.push_back(run.command);
    const Results& r = run.results;
    for (const auto& [name, value] : r.metrics)
      c.results->metrics["temporal_" + std::string(run_def.scene) + "_" + run_def.path + "_" + name] = value;
    quality.rows.push_back({where, metric(r, "temporal_mae_avg"), metric(r, "direct_mae_avg"),
                            metric(r, "recompute_pct_avg"), metric(r, "keyframe_interval_avg"),
                            metric(r, "speedup_vs_reference"), metric(r, "frame_speedup_vs_reference"),
                            std::string(run_def.thesis_speedup)});
    paths.push_back(where);
    series.push_back(recompute_series(r));
    if (&run_def == &kRuns[0]) add_images(c, section, run, where);
  }
  const Table per_frame_plot = per_frame_table(paths, series);
  for (const Table* t : {static_cast<const Table*>(&quality), &per_frame_plot}) {
    c.results->tables.push_back(*t);
    section.tables.push_back(t->title);
  }
  section.plots.push_back({"Recompute fraction per frame (key frames at the spikes)", per_frame_plot.title, "line",
                           "frame", paths, "frame", "% of reflective pixels recomputed"});
  c.results->sections.push_back(section);
}

}  // namespace proxima::cli::demo
