// Demo section: reflections from clustered depth images (thesis ch. 4; docs/cluster_reflections.md).
#include "demo_sections.h"
#include "proxima/eval/image_error.h"
#include "proxima/scene/load.h"
#include "proxima/study/cluster_reflect.h"

namespace proxima::study::demo {

namespace {

struct Run {
  const char* scene;
  const char* path;
  const char* thesis_mae;        // §4.7.1, per channel r / g / b
  const char* thesis_occlusion;  // % of samples, avg / max
  const char* thesis_fps;        // Table 13: cluster (GPU) vs OptiX
};
constexpr Run kQuick[] = {{"living-room", "walk", "6 / 3 / 9", "0.62 / 1.3", "18 / 15 vs 1.1 / 1.0"},
                          {"bathroom", "walk", "6 / 3 / 9", "2.75 / 3.5", "17 / 18 vs 3.3 / 2.3"}};
constexpr Run kFull[] = {{"living-room", "walk", "6 / 3 / 9", "0.62 / 1.3", "18 / 15 vs 1.1 / 1.0"},
                         {"living-room", "orbit", "6 / 3 / 9", "0.62 / 1.3", "18 / 15 vs 1.1 / 1.0"},
                         {"bathroom", "walk", "6 / 3 / 9", "2.75 / 3.5", "17 / 18 vs 3.3 / 2.3"},
                         {"bathroom", "pan", "6 / 3 / 9", "2.75 / 3.5", "17 / 18 vs 3.3 / 2.3"}};

struct Settings {
  int size, frame_step;
};
Settings settings(const Context& c) { return c.full ? Settings{512, 90} : Settings{256, 300}; }

Section intro(const Settings& s) {
  const int frames = 900 / s.frame_step;
  return {"cluster", "Cluster depth-image reflections (thesis ch. 4)",
          "Reflective samples of the G-buffer are clustered in screen space; each cluster gets a camera "
          "and a depth image of the scene as seen from it, and every reflected (or glossy lobe) ray is "
          "intersected with its cluster's depth image instead of the scene. Compared with Embree "
          "tracing the identical rays with identical shading, so the errors are the approximation's "
          "alone. docs/cluster_reflections.md.\n\n"
          "This run: " + std::to_string(s.size) + "² output, 2×2 samples per pixel, 8 lobe rays on glossy "
              "surfaces, every " + std::to_string(s.frame_step) + "th of 900 path frames (" +
              std::to_string(frames) + " frames per path). The thesis ran a GPU against OptiX on its own "
              "models; ours are procedural stand-ins on the CPU against Embree.",
          {}, {}, {}};
}

struct Tables {
  Table error{"Error vs Embree on the same rays, beside thesis §4.7.1 (0–255 per channel; occlusion errors % of samples)",
              {"scene / path", "mae r", "mae g", "mae b", "thesis mae r / g / b", "occlusion avg", "occlusion max",
               "occlusion, mirror samples avg", "thesis occlusion avg / max"},
              {}};
  Table fps{"Frame rate beside thesis Table 13 (fps)",
            {"scene / path", "reflective % avg", "Embree fps avg", "cluster fps avg", "Embree ms ÷ cluster ms",
             "thesis cluster vs OptiX fps"},
            {}};
  Table steps{"Step times, ms avg (thesis Table 14: 0.5–0.6 / 20–24 / 24–28 / 7–14 on its GPU)",
              {"scene / path", "G-buffer + clustering", "cluster cameras", "depth images", "intersection"}, {}};
  Table ssr{"Screen-space reflections with box-probe fallback beside cluster and env mapping (MAE 0–255, channels "
            "averaged, vs Embree on the same rays; ms per frame)",
            {"scene / path", "ssr mae", "ssr fallback % of samples", "boxprobe mae", "cluster mae",
             "rectified mae", "ssr ms", "boxprobe ms", "cluster ms", "rectified ms", "Embree ms"},
            {}};

  void add(const std::string& where, const Run& run_def, const Results& r) {
    error.rows.push_back({where, metric(r, "cluster_mae_r"), metric(r, "cluster_mae_g"), metric(r, "cluster_mae_b"),
                          std::string(run_def.thesis_mae), metric(r, "occlusion_error_pct_avg"),
                          metric(r, "occlusion_error_pct_max"), metric(r, "occlusion_error_mirror_pct_avg"),
                          std::string(run_def.thesis_occlusion)});
    fps.rows.push_back({where, metric(r, "reflective_pct_avg"), 1000.0 / metric(r, "reference_ms_avg"),
                        1000.0 / metric(r, "cluster_ms_avg"), metric(r, "speedup_static"),
                        std::string(run_def.thesis_fps)});
    steps.rows.push_back({where, metric(r, "gbuffer_clustering_ms_avg"), metric(r, "cluster_cameras_ms_avg"),
                          metric(r, "depth_images_ms_avg"), metric(r, "intersection_ms_avg")});
    auto avg = [&](const std::string& m) {
      return (metric(r, m + "_mae_r") + metric(r, m + "_mae_g") + metric(r, m + "_mae_b")) / 3.0;
    };
    ssr.rows.push_back({where, avg("ssr"), metric(r, "ssr_fallback_pct_avg"), avg("boxprobe"), avg("cluster"),
                        avg("envmap"), metric(r, "ssr_ms_avg"), metric(r, "boxprobe_ms_avg"),
                        metric(r, "cluster_ms_avg"), metric(r, "envmap_ms_avg"), metric(r, "reference_ms_avg")});
  }
};

// One path through the study, with the command line that reproduces it.
StudyRun run_path(Context& c, const Run& run_def, const Settings& s) {
  // --method ssr: the cluster study with SSR (box-probe fallback) beside it on the same rays.
  const std::vector<std::string> args = {"reflect", "--method", "ssr", "--scene", run_def.scene, "--path",
                                         run_def.path, "--frames", "900", "--frame-step",
                                         std::to_string(s.frame_step), "--width", std::to_string(s.size),
                                         "--height", std::to_string(s.size), "--ss", "2", "--gloss-rays", "8",
                                         "--compare", "--seed", std::to_string(c.seed)};
  study::ClusterReflectOptions o;
  o.camera.path = run_def.path;
  o.frames = 900;
  o.frame_step = s.frame_step;
  o.width = o.height = s.size;
  o.reflection.supersample = 2;
  o.reflection.glossy_rays = 8;
  o.compare = true;
  o.ssr = true;
  o.reflection.seed = c.seed;
  const Scene scene = load_scene(run_def.scene);
  return run_study(c, std::string("cluster/") + run_def.scene + "-" + run_def.path, args,
                   [&](const study::StudyOutput& out) { return study::run_cluster_reflect(scene, o, out); });
}

// Images of the first frame, the heat map on the reflection sections' common scale.
void add_images(Context& c, Section& section, const StudyRun& run, const std::string& where, const Settings& s) {
  auto it = run.results.images.find("cluster");
  const std::string color_file =
      run.dir + "/" + (it != run.results.images.end() ? it->second : std::string("cluster.png"));
  const ImageF color = read_study_image(c, color_file);
  const ImageF reference = read_study_image(c, run.dir + "/reference.png");
  const ImageF err = error_image(color, reference);
  add_image(c, section, where + ": Embree, same rays", run.dir + "/reference.png");
  add_image(c, section, where + ": cluster depth images", color_file);
  write_image(c, section, where + ": error", run.dir + "/heat.png", error_heatmap(err, kErrorHeatmapMax));
  add_image(c, section, where + ": clusters (red: environment fallback, yellow: occlusion error)",
            run.dir + "/clusters.png");
  add_heatmap_legend(c, section, kErrorHeatmapMax);
  const Window w = worst_window(err, std::max(24, s.size / 8));
  const int zoom = std::max(2, 192 / w.size);
  write_image(c, section, "zoom ×" + std::to_string(zoom) + ": Embree", run.dir + "/zoom_reference.png",
              crop_zoom(reference, w, zoom));
  write_image(c, section, "zoom ×" + std::to_string(zoom) + ": cluster", run.dir + "/zoom_color.png",
              crop_zoom(color, w, zoom));
  write_image(c, section, "zoom ×" + std::to_string(zoom) + ": error", run.dir + "/zoom_heat.png",
              crop_zoom(error_heatmap(err, kErrorHeatmapMax), w, zoom));
  // The baselines on the same frame: SSR with its fallback, and the box probe alone.
  for (const char* m : {"ssr", "boxprobe"}) {
    const std::string file = run.dir + "/" + m + ".png";
    const std::string name = std::string(m) == "ssr" ? "SSR + box-probe fallback" : "box probe alone";
    add_image(c, section, where + ": " + name, file);
    write_image(c, section, where + ": error of " + name, run.dir + "/heat_" + m + ".png",
                error_heatmap(error_image(read_study_image(c, file), reference), kErrorHeatmapMax));
  }
  add_image(c, section, where + ": SSR fallback (red: share of the pixel's rays from the box probe)",
            run.dir + "/ssr_fallback.png");
}

}  // namespace

int cluster_steps(const Context& c) { return c.full ? int(std::size(kFull)) : int(std::size(kQuick)); }

void cluster_section(Context& c) {
  const Settings s = settings(c);
  Section section = intro(s);
  Tables tables;
  const Run* runs = c.full ? kFull : kQuick;
  const int n = cluster_steps(c);
  for (int i = 0; i < n; ++i) {
    const Run& run_def = runs[i];
    const std::string where = std::string(run_def.scene) + " / " + run_def.path;
    const StudyRun run = run_path(c, run_def, s);
    section.commands.push_back(run.command);
    for (const auto& [name, value] : run.results.metrics)
      c.results->metrics["cluster_" + std::string(run_def.scene) + "_" + run_def.path + "_" + name] = value;
    tables.add(where, run_def, run.results);
    if (i == 0) add_images(c, section, run, where, s);
  }
  for (Table* t : {&tables.error, &tables.fps, &tables.steps, &tables.ssr}) {
    c.results->tables.push_back(*t);
    section.tables.push_back(t->title);
  }
  section.plots.push_back({"Where a cluster frame's time goes", tables.steps.title, "bar", "scene / path",
                           {"G-buffer + clustering", "cluster cameras", "depth images", "intersection"}, "",
                           "ms per frame"});
  section.plots.push_back({"Frame rate: Embree vs cluster depth images", tables.fps.title, "bar", "scene / path",
                           {"Embree fps avg", "cluster fps avg"}, "", "frames per second"});
  c.results->sections.push_back(section);
}

}  // namespace proxima::study::demo
