// Demo section: depth-image sampling (thesis ch. 2; `proxima sample`, docs/depthimage.md).
#include <algorithm>

#include "demo_sections.h"
#include "proxima/scene/load.h"
#include "proxima/study/sampling.h"

namespace proxima::study::demo {

namespace {

const char* const kScenes[] = {"nest", "grass", "city", "tree"};

struct Settings {
  int width, frames, reps;
};
Settings settings(const Context& c) { return c.full ? Settings{1024, 1000, 3} : Settings{256, 100, 1}; }

// The thesis' Tables 2 and 4 (pixel redundancy, 1024², K = 1000), as quoted in docs/journal/sampling.md:
// conventional redundant %, NRR occluded (useful) %, peeling occluded (useful) % for V0..V2,
// then available avg / min for conventional, NRR, peeling.
struct ThesisRow {
  double conv[3], nrr_occ[3], nrr_use[3], peel_occ[3], peel_use[3], avail[6];
};
constexpr ThesisRow kThesis[] = {
    {{0, 70, 80}, {0, 62, 76}, {0, 89, 86}, {10, 46, 52}, {99, 2, 71}, {90, 89, 93, 92, 92, 89}},
    {{0, 54, 69}, {0, 56, 75}, {0, 85, 80}, {15, 51, 71}, {99, 4, 79}, {86, 81, 96, 91, 93, 88}},
    {{0, 82, 84}, {0, 73, 80}, {0, 40, 23}, {1, 78, 88}, {100, 7, 8}, {97, 96, 98, 97, 96, 91}},
    {{0, 23, 35}, {0, 84, 88}, {0, 99, 98}, {44, 63, 72}, {99, 98, 97}, {55, 53, 59, 57, 55, 48}},
};

std::string pct3(const double* v) { return fixed(v[0], 0) + "% / " + fixed(v[1], 0) + "% / " + fixed(v[2], 0) + "%"; }
std::string occ3(const double* occ, const double* use) {
  std::string s;
  for (int i = 0; i < 3; ++i)
    s += (i ? " / " : "") + fixed(occ[i], 0) + "% (" + fixed(use[i], 0) + "%)";
  return s;
}

Section intro(const Settings& s) {
  const std::string size = std::to_string(s.width) + "²";
  return {"sampling", "Depth-image sampling: conventional, depth peeling, NRR (thesis ch. 2)",
          "Three depth images sample each scene from the corners of a small view triangle (conventional: "
          "each view on its own; NRR: later views keep only samples no earlier image holds; depth peeling: "
          "3 layers from the triangle's centroid). The metrics are the thesis': redundant samples, "
          "occluded samples (hidden from the first view) and how many of them are useful, and the share "
          "of each intermediate output frame's samples the set makes available. Method and metric "
          "definitions: docs/depthimage.md.\n\n"
          "This run: " + size + " images, K = " + std::to_string(s.frames) + " output frames, " +
              std::to_string(s.reps) + " timed repetition(s); the thesis used 1024², K = 1000. Our scenes are "
              "procedural stand-ins near the thesis' triangle counts, not its models, so the rows differ "
              "in what they show (see docs/journal/sampling.md).",
          {}, {}, {}};
}

struct Tables {
  Table metrics, avail, timing;
};

Tables make_tables(const Settings& s) {
  const std::string size = std::to_string(s.width) + "²";
  return {{"Sampling metrics beside thesis Tables 2 and 4 (pixel redundancy), V0 / V1 / V2",
           {"scene", "conventional: redundant", "NRR: occluded (useful)", "peeling: occluded (useful)"}, {}},
          {"Available samples per output frame, % (thesis Table 4)",
           {"scene", "conventional avg", "conventional min", "NRR avg", "NRR min", "peeling avg", "peeling min",
            "thesis conventional avg", "thesis NRR avg", "thesis peeling avg"},
           {}},
          {"Sampling time, 3 images of " + size + " (ms)",
           {"scene", "triangles", "conventional_ms", "peeling_ms", "nrr_ms", "nrr_over_conventional",
            "nrr_over_peeling"},
           {}}};
}

// One scene's rows beside the thesis' (kThesis[k]).
void add_rows(Tables& t, const std::string& scene, const Results& r, const ThesisRow& thesis) {
  double conv[3], no[3], nu[3], po[3], pu[3];
  for (int i = 0; i < 3; ++i) {
    const std::string v = std::to_string(i);
    conv[i] = metric(r, "conventional_redundant_pct_" + v);
    no[i] = metric(r, "nrr_pixel_occluded_pct_" + v);
    nu[i] = metric(r, "nrr_pixel_useful_pct_" + v);
    po[i] = metric(r, "peeling_occluded_pct_" + v);
    pu[i] = metric(r, "peeling_useful_pct_" + v);
  }
  t.metrics.rows.push_back({scene, pct3(conv), occ3(no, nu), occ3(po, pu)});
  t.metrics.rows.push_back({scene + ", thesis", pct3(thesis.conv), occ3(thesis.nrr_occ, thesis.nrr_use),
                            occ3(thesis.peel_occ, thesis.peel_use)});
  t.avail.rows.push_back({scene, metric(r, "conventional_available_avg_pct"),
                          metric(r, "conventional_available_min_pct"), metric(r, "nrr_pixel_available_avg_pct"),
                          metric(r, "nrr_pixel_available_min_pct"), metric(r, "peeling_available_avg_pct"),
                          metric(r, "peeling_available_min_pct"), thesis.avail[0], thesis.avail[2], thesis.avail[4]});
  const double tc = metric(r, "conventional_time_ms"), tp = metric(r, "peeling_time_ms"),
               tn = metric(r, "nrr_pixel_time_ms");
  t.timing.rows.push_back({scene, metric(r, "triangles"), tc, tp, tn, tn / tc, tn / tp});
}

// The study on one scene: its metrics into the report, its rows, its command, and for
// grass the images of view V1.
void run_scene(Context& c, Section& section, Tables& t, const Settings& s, size_t k) {
  const std::string scene = kScenes[k];
  study::SamplingOptions o;  // what the reproducing command gives
  o.methods = {study::SamplingMethod::Conventional, study::SamplingMethod::Peeling, study::SamplingMethod::NrrPixel};
  o.width = o.height = s.width;
  o.frames = s.frames;
  o.reps = s.reps;
  o.seed = c.seed;
  StudyRun run = run_study(c, "sampling/" + scene,
                           {"sample", "--scene", scene, "--method", "conventional,peeling,nrr-pixel", "--width",
                            std::to_string(s.width), "--frames", std::to_string(s.frames), "--reps",
                            std::to_string(s.reps), "--seed", std::to_string(c.seed)},
                           [&](const study::StudyOutput& out) {
                             return study::run_sampling(load_scene(scene), o, out);
                           });
  const Results& r = run.results;
  add_rows(t, scene, r, kThesis[k]);
  for (const auto& [name, value] : r.metrics) c.results->metrics["sampling_" + scene + "_" + name] = value;
  section.commands.push_back(run.command);
  if (scene != "grass") return;
  for (const char* img : {"conventional_1_color", "nrr-pixel_1_color", "nrr-pixel_1_occluded", "peeling_1_occluded"}) {
    auto it = r.images.find(img);
    if (it != r.images.end()) add_image(c, section, "grass: " + std::string(img), run.dir + "/" + it->second);
  }
}

}  // namespace

int sampling_steps(const Context&) { return int(std::size(kScenes)); }

void sampling_section(Context& c) {
  const Settings s = settings(c);
  Section section = intro(s);
  Tables t = make_tables(s);
  for (size_t k = 0; k < std::size(kScenes); ++k) run_scene(c, section, t, s, k);
  std::sort(t.timing.rows.begin(), t.timing.rows.end(),
            [](const auto& a, const auto& b) { return std::get<double>(a[1]) < std::get<double>(b[1]); });
  section.text += "\n\nImages (grass, view V1): what each method's second image holds; in the *_occluded images "
                  "green marks samples hidden from V0 and yellow those among them that are useful to some output "
                  "frame (thesis Table 3 colours).";
  section.tables = {t.metrics.title, t.avail.title, t.timing.title};
  section.plots.push_back({"Available samples per output frame", t.avail.title, "bar", "scene",
                           {"conventional avg", "NRR avg", "peeling avg", "thesis NRR avg"}, "scene", "% of samples"});
  section.plots.push_back({"Sampling time vs triangle count", t.timing.title, "line", "triangles",
                           {"conventional_ms", "peeling_ms", "nrr_ms"}, "triangles", "ms for 3 images"});
  c.results->tables.push_back(t.metrics);
  c.results->tables.push_back(t.avail);
  c.results->tables.push_back(t.timing);
  c.results->sections.push_back(section);
}

}  // namespace proxima::study::demo
