// Demo section: soft shadows from depth images reconstructed into meshes (thesis ch. 3;
// `proxima shadows`, docs/shadows.md).
#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "demo.h"
#include "proxima/eval/image_error.h"
#include "proxima/scene/load.h"
#include "proxima/study/shadows.h"

namespace proxima::cli::demo {

namespace {

struct Settings {
  int ref_res, out_res, light_samples;
  std::vector<double> light_sizes;
};
Settings settings(const Context& c) {
  if (c.full) return {1024, 512, 16, {0.25, 0.5, 1.0, 2.0, 4.0}};
  return {512, 256, 8, {0.5, 1.0, 2.0}};
}

std::string size_arg(double v) { return fixed(v, v < 1.0 ? 2 : 0); }

// The options the reproducing command in run_light gives (--light-size as printed).
study::ShadowsOptions options(const Settings& s, double light_size) {
  study::ShadowsOptions o;
  o.samplings = {ShadowSampling::Nrr, ShadowSampling::Conventional, ShadowSampling::Peeling};
  o.light_size = std::stof(size_arg(light_size));
  o.light_samples = s.light_samples;
  o.ref_res = s.ref_res;
  o.out_res = s.out_res;
  return o;
}

Section intro(const Settings& s) {
  return {"shadows", "Soft shadows from reconstructed depth images (thesis ch. 3)",
          "Depth images of the scene from the area light's four corners (non-redundant rendering or "
          "conventional) or four depth-peeling layers from its centre are reconstructed into meshes "
          "(hybrid reconstruction, Algorithm 4); every one of n×n light samples then rasterizes a shadow "
          "map of those meshes instead of the scene (Algorithm 5). Errors per pixel count the light "
          "samples whose visibility is wrong (visibility error) and the difference of lit samples "
          "(intensity error), 0–255, against the same shadow maps of the original geometry (the thesis' "
          "ground truth); exact Embree shadow rays are reported too. docs/shadows.md.\n\n"
          "This run: city, reference images " + std::to_string(s.ref_res) + "², output " +
              std::to_string(s.out_res) + "², " + std::to_string(s.light_samples) + "×" +
              std::to_string(s.light_samples) + " light samples. Thesis (city, 1024², Table 9 means, "
              "intensity · visibility): NRR 1.60 · 2.07, conventional 3.46 · 3.64, peeling 11.3 · 12.6.",
          {}, {}, {}};
}

struct Tables {
  Table errors, times;
};

// The light-size-1 run's figures: time per step, every shadow and error image, and a
// close-up of the penumbra where NRR errs most.
void add_light1_figures(Context& c, Section& section, Tables& t, const ChildRun& run, const Settings& s) {
  for (const char* sampling : {"nrr", "conventional", "peeling"}) {
    const std::string p = std::string(sampling) + "_";
    t.times.rows.push_back({std::string(sampling), metric(run.results, p + "time_reference_ms"),
                            metric(run.results, p + "time_reconstruct_ms"), metric(run.results, p + "time_shadow_ms")});
  }
  add_image(c, section, "light 1: geometry shadow maps (ground truth)", run.dir + "/geometry_shadow.png");
  add_image(c, section, "light 1: Embree shadow rays", run.dir + "/rays_shadow.png");
  for (const char* sampling : {"nrr", "conventional", "peeling"}) {
    add_image(c, section, std::string("light 1: ") + sampling, run.dir + "/" + sampling + "_shadow.png");
    add_image(c, section, std::string("light 1: ") + sampling + " error (green too bright, red too dark)",
              run.dir + "/" + sampling + "_error.png");
  }
  const ImageF truth = read_child_image(c, run.dir + "/geometry_shadow.png");
  const ImageF nrr = read_child_image(c, run.dir + "/nrr_shadow.png");
  const Window w = worst_window(error_image(nrr, truth), std::max(24, s.out_res / 8));
  const int zoom = std::max(2, 192 / w.size);
  write_image(c, section, "zoom ×" + std::to_string(zoom) + ": geometry", run.dir + "/zoom_geometry.png",
              crop_zoom(truth, w, zoom));
  write_image(c, section, "zoom ×" + std::to_string(zoom) + ": NRR", run.dir + "/zoom_nrr.png",
              crop_zoom(nrr, w, zoom));
}

// The study on city with one light size: its metrics into the report, its row, its command.
void run_light(Context& c, Section& section, Tables& t, const Settings& s, double size) {
  const std::string label = size_arg(size);
  std::vector<std::string> args = {"shadows", "--scene", "city", "--sampling", "nrr,conventional,peeling",
                                   "--light-size", label, "--light-samples", std::to_string(s.light_samples),
                                   "--ref-res", std::to_string(s.ref_res), "--out-res", std::to_string(s.out_res)};
  ChildRun run = run_study(c, "shadows/city-light-" + label, args, [&](const study::StudyOutput& out) {
    return study::run_shadows(load_scene("city"), options(s, size), out);
  });
  section.commands.push_back(run.command);
  const Results& r = run.results;
  for (const auto& [name, value] : r.metrics) c.results->metrics["shadows_city_light_" + label + "_" + name] = value;
  t.errors.rows.push_back({size, metric(r, "nrr_visibility_error_mean"),
                           metric(r, "conventional_visibility_error_mean"), metric(r, "peeling_visibility_error_mean"),
                           metric(r, "nrr_intensity_error_mean"), metric(r, "conventional_intensity_error_mean"),
                           metric(r, "peeling_intensity_error_mean")});
  if (size == 1.0) add_light1_figures(c, section, t, run, s);
}

}  // namespace

int shadows_steps(const Context& c) { return int(settings(c).light_sizes.size()); }

void shadows_section(Context& c) {
  const Settings s = settings(c);
  Section section = intro(s);
  Tables t{{"Soft-shadow mean errors on city vs light size (0–255; vs shadow maps of the geometry)",
            {"light size (× scene diagonal)", "NRR visibility", "conventional visibility", "peeling visibility",
             "NRR intensity", "conventional intensity", "peeling intensity"},
            {}},
           {"Soft-shadow time per step on city, light size 1 (thesis Table 11 shape), ms",
            {"sampling", "1: reference images", "2: reconstruction", "3: soft shadows"}, {}}};
  for (double size : s.light_sizes) run_light(c, section, t, s, size);
  for (Table* table : {&t.errors, &t.times}) {
    c.results->tables.push_back(*table);
    section.tables.push_back(table->title);
  }
  section.plots.push_back({"Mean visibility error vs light size (city)", t.errors.title, "line",
                           "light size (× scene diagonal)",
                           {"NRR visibility", "conventional visibility", "peeling visibility"},
                           "light size (× scene diagonal)", "mean visibility error (0–255)"});
  c.results->sections.push_back(section);
}

}  // namespace proxima::cli::demo
