#include "proxima/study/technique_bench.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "proxima/core/error.h"
#include "proxima/core/range_check.h"
#include "proxima/core/timer.h"
#include "proxima/reflect/ssr_reflection.h"
#include "proxima/scene/camera_path.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/load.h"
#include "proxima/study/catalog.h"
#include "proxima/study/demo.h"
#include "proxima/study/sampling.h"
#include "proxima/study/visibility.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::study {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One study run of a technique at one setting; `measure` runs it once and returns its
// metrics (with "embree_ms" added where the study does not time Embree itself).
struct Case {
  std::string technique, where, knob;
  double knob_value = 0;
  bool demo = false;
  std::function<std::map<std::string, double>()> measure;
};

double get(const std::map<std::string, double>& m, const std::string& name) {
  auto it = m.find(name);
  return it == m.end() ? kNaN : it->second;
}

// Median ms of Embree item buffers (depth, triangle id, normal, position) of `cameras`
// with a BVH built beforehand; the build time as "embree_build_ms".
void time_item_buffers(const Scene& scene, const std::vector<Camera>& cameras, std::map<std::string, double>& m) {
  Stopwatch build;
  const RayScene rays(scene);
  m["embree_build_ms"] = build.elapsed_ms();
  Stopwatch w;
  for (const Camera& cam : cameras) (void)trace_item_buffer(scene, rays, cam);
  m["embree_ms"] = w.elapsed_ms();
}

// --- The demo's quick settings and the swept knobs. The reflection and shadow points run the
// demo's own study runs (study::plan_demo, through the catalog) with the knob changed, so the
// bench cannot drift from the demo; sampling and visibility keep typed options here, since
// Embree's item buffers need their views. ---

// The demo's quick run of `study` on `scene` (the first one, or the first with `option` =
// `value`), as the catalog runs it.
CatalogRun demo_run(uint64_t seed, const std::string& study, const std::string& scene, const std::string& option = "",
                    const OptionValue& value = {}) {
  DemoOptions d;
  d.seed = seed;
  for (const DemoStudyRun& r : plan_demo(d)) {
    CatalogRun c = catalog_run_from_command(r.args);
    if (c.study == study && c.scene == scene &&
        (option.empty() || (c.options.count(option) && c.options.at(option) == value)))
      return c;
  }
  throw std::logic_error("technique bench: the demo plans no " + study + " run on " + scene);
}

// The value of option `name` of `run` as the study sees it (the demo's or the default).
double option_value(const CatalogRun& run, const std::string& name) {
  const OptionValue v = resolved_options(run.study, run.options).at(name);
  if (const std::int64_t* i = std::get_if<std::int64_t>(&v)) return double(*i);
  return std::get<double>(v);
}

// `run` with option `knob` at `value` (an int option takes it as an integer), beside its
// Embree reference as the study times it.
Case catalog_case(const std::string& technique, const std::string& where, const std::string& knob_name,
                  CatalogRun run, const std::string& knob, double value) {
  const bool demo = value == option_value(run, knob);
  if (std::holds_alternative<std::int64_t>(resolved_options(run.study, run.options).at(knob)))
    run.options[knob] = std::int64_t(value);
  else
    run.options[knob] = value;
  return {technique, where, knob_name, value, demo,
          [run] { return run_study(run.study, load_scene(run.scene), run.options, {}).metrics; }};
}

Case sampling_case(uint64_t seed, int size, bool demo) {
  return {"sampling", "city", "image side", double(size), demo, [=] {
            SamplingOptions o;
            o.methods = {SamplingMethod::Conventional, SamplingMethod::Peeling, SamplingMethod::NrrPixel};
            o.width = o.height = size;
            o.frames = 100;
            o.reps = 1;
            o.seed = seed;
            const Scene scene = load_scene("city");
            std::map<std::string, double> m = run_sampling(scene, o, {}).metrics;
            time_item_buffers(scene, sampling_views(scene, o).corners, m);
            return m;
          }};
}

Case visibility_case(int size, bool demo) {
  return {"visibility", "floor", "image side", double(size), demo, [=] {
            VisibilityOptions o;
            o.width = o.height = size;
            o.frames = 10;
            o.images = false;
            const Scene scene = load_scene("floor");
            std::map<std::string, double> m = run_visibility(scene, o, {}).metrics;
            const CameraPath& path = scene.camera_paths.front();
            std::vector<Camera> cams;
            for (int f = 0; f < std::min(o.frames, path.frames); ++f)
              cams.push_back(camera_at_time(path, frame_time(path, f), size, size, 1e-3f, scene_far_plane(scene)));
            time_item_buffers(scene, cams, m);
            m["embree_ms"] /= double(cams.size());  // per viewpoint, as map_ms_avg
            return m;
          }};
}

std::vector<Case> cases_of(const std::string& technique, uint64_t seed, bool demo, bool sweep) {
  std::vector<Case> c;
  auto add_case = [&](Case k) {
    if (k.demo ? demo : sweep) c.push_back(std::move(k));
  };
  if (technique == "envmap") {
    CatalogRun run = demo_run(seed, "envmap_reflect", "room-reflector");
    run.options["reps"] = std::int64_t{1};  // the bench's repetitions are the medians' samples
    for (int cube : {64, 128, 256, 512})
      add_case(catalog_case("envmap", "room-reflector", "cube size", run, "cube_size", cube));
  }
  for (const char* scene : {"living-room", "bathroom"}) {
    const std::string where = std::string(scene) + " walk";
    // SSR (the demo's cluster runs carry it) does not depend on the cluster images' resolution
    // scale: it runs beside the demo's setting only.
    if (technique == "cluster") {
      const CatalogRun run = demo_run(seed, "cluster_reflect", scene);
      add_case(catalog_case("cluster", where, "resolution scale", run, "resolution_scale",
                            option_value(run, "resolution_scale")));
      CatalogRun other = run;
      other.options["ssr"] = false;
      // Lobe rays per glossy sample: the per-image work stays, the per-ray work grows on both
      // sides, so this is the knob along which the method can cross Embree.
      if (std::string(scene) == "living-room") {
        for (double v : {0.5, 2.0})
          add_case(catalog_case("cluster", where, "resolution scale", other, "resolution_scale", v));
        for (int rays : {32, 128})
          add_case(catalog_case("cluster", where, "glossy rays", other, "glossy_rays", rays));
      }
    }
    if (technique == "temporal") {
      const CatalogRun run = demo_run(seed, "temporal_reflect", scene);
      add_case(catalog_case("temporal", where, "key-frame threshold", run, "threshold",
                            option_value(run, "threshold")));
      if (std::string(scene) == "living-room")
        for (double v : {0.1, 0.6})
          add_case(catalog_case("temporal", where, "key-frame threshold", run, "threshold", v));
    }
  }
  if (technique == "sampling")
    for (int size : {128, 256, 512}) add_case(sampling_case(seed, size, size == 256));
  if (technique == "shadows") {
    const CatalogRun run = demo_run(seed, "shadows", "city", "light_size", 1.0);
    for (int res : {256, 512, 1024})
      add_case(catalog_case("shadows", "city", "shadow-map side", run, "shadow_res", res));
  }
  if (technique == "visibility")
    for (int size : {128, 256, 1024}) add_case(visibility_case(size, size == 256));
  return c;
}

std::vector<std::string> chosen(const std::string& list) {
  if (list == "all") return technique_bench_names();
  std::vector<std::string> names;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');) {
    const auto& all = technique_bench_names();
    if (std::find(all.begin(), all.end(), name) == all.end()) {
      std::string valid = "all";
      for (const std::string& n : all) valid += ", " + n;
      fail_input("--techniques: unknown technique '" + name + "' (" + valid + ")");
    }
    names.push_back(name);
  }
  if (names.empty()) fail_input("--techniques: empty list");
  return names;
}

}  // namespace

const std::vector<std::string>& technique_bench_names() {
  static const std::vector<std::string> names{"envmap", "cluster", "temporal", "sampling", "shadows", "visibility"};
  return names;
}

void validate(const TechniqueBenchOptions& o) {
  (void)chosen(o.techniques);
  require_in_range(o.reps, 1, 100, "--reps");
}

std::vector<TechniquePoint> technique_points(const std::string& technique, const std::string& where,
                                             const std::string& knob, double knob_value, bool demo,
                                             const std::function<double(const std::string&)>& m) {
  std::vector<TechniquePoint> p;
  auto point = [&](const std::string& method, double ms, double ref, double error, const std::string& unit) {
    TechniquePoint t{technique, method, knob, knob_value, demo, ms, ref, 0, 0, error, unit};
    p.push_back(t);
    return &p.back();
  };
  if (technique == "envmap") {
    for (const char* method : {"envmap", "rectified", "average", "layered", "boxprobe"}) {
      TechniquePoint* t = point(method, m(std::string(method) + "_ms"), m("reference_ms"),
                                m(std::string(method) + "_mae"), "MAE 0–255");
      t->approximation_build_ms = m(std::string(method) + "_with_build_ms") - t->ms;
    }
  } else if (technique == "cluster") {
    auto mae = [&](const std::string& pre) {
      return (m(pre + "_mae_r") + m(pre + "_mae_g") + m(pre + "_mae_b")) / 3.0;
    };
    const double embree_build = m("reference_dynamic_ms_avg") - m("reference_ms_avg");
    point(where, m("cluster_ms_avg"), m("reference_ms_avg"), mae("cluster"), "MAE 0–255")->reference_build_ms =
        embree_build;
    // A run with ssr: SSR with its box-probe fallback on the same frames and rays. Its frame
    // time is the shared G-buffer step, its own depth, back-face and pyramid passes, and the
    // walk with shading and fallback lookups; the fallback's cube map, built once per frame,
    // is its preparation, as the env-map points count their cube build.
    if (std::isfinite(m("ssr_ms_avg"))) {
      TechniquePoint* t = point("ssr " + where, m("ssr_ms_avg"), m("reference_ms_avg"), mae("ssr"), "MAE 0–255");
      t->knob = "max steps";
      t->knob_value = SsrOptions{}.max_steps;
      t->reference_build_ms = embree_build;
      t->approximation_build_ms = m("probe_build_ms_avg");
    }
  } else if (technique == "temporal") {
    point(where + ", reflections", m("temporal_ms_avg"), m("reference_ms_avg"), m("temporal_mae_avg"), "MAE 0–255");
    point(where + ", whole frame", m("frame_temporal_ms_avg"), m("frame_reference_ms_avg"), m("temporal_mae_avg"),
          "MAE 0–255");
  } else if (technique == "sampling") {
    for (const char* method : {"conventional", "peeling", "nrr_pixel"}) {
      TechniquePoint* t = point(method, m(std::string(method) + "_time_ms"), m("embree_ms"),
                                100.0 - m(std::string(method) + "_available_avg_pct"), "% samples missing");
      t->reference_build_ms = m("embree_build_ms");
    }
  } else if (technique == "shadows") {
    for (const char* method : {"nrr", "conventional", "peeling"}) {
      const std::string pre = std::string(method) + "_";
      TechniquePoint* t = point(method, m(pre + "time_shadow_ms"), m("time_rays_ms"),
                                m(pre + "visibility_error_rays_mean"), "visibility error 0–255");
      t->approximation_build_ms = m(pre + "time_reference_ms") + m(pre + "time_reconstruct_ms");
    }
  } else if (technique == "visibility") {
    TechniquePoint* t =
        point(where, m("map_ms_avg"), m("embree_ms"), 100.0 - m("agreement_pct"), "% pixels disagreeing");
    t->approximation_build_ms = m("build_ms");
    t->reference_build_ms = m("embree_build_ms");
  }
  return p;
}

std::vector<TechniquePoint> measure_techniques(const TechniqueBenchOptions& o, bool demo_settings,
                                               Progress* progress) {
  validate(o);
  std::vector<Case> cases;
  for (const std::string& t : chosen(o.techniques))
    for (Case& c : cases_of(t, o.seed, demo_settings, o.sweep)) cases.push_back(std::move(c));
  // runs[i][r]: case i's metrics in repetition r; repetitions interleave the cases.
  std::vector<std::vector<std::map<std::string, double>>> runs(cases.size());
  if (progress) progress->begin("techniques vs Embree", int(cases.size()) * o.reps);
  for (int r = 0; r < o.reps; ++r)
    for (size_t i = 0; i < cases.size(); ++i) {
      if (progress) progress->step(cases[i].technique + " " + cases[i].where);
      runs[i].push_back(cases[i].measure());
    }
  if (progress) progress->end();
  std::vector<TechniquePoint> points;
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    // Times are medians over the repetitions; errors are deterministic (the same every run).
    auto m = [&](const std::string& name) {
      std::vector<double> v;
      for (const auto& run : runs[i]) v.push_back(get(run, name));
      return median(v);
    };
    for (TechniquePoint& p : technique_points(c.technique, c.where, c.knob, c.knob_value, c.demo, m))
      points.push_back(std::move(p));
  }
  return points;
}

namespace {

std::string metric_name(const TechniquePoint& p) {
  std::string out;  // ' ', '/', ',' as '_', runs of '_' as one
  for (char ch : p.technique + "_" + p.method) {
    if (ch == ' ' || ch == '/' || ch == ',') ch = '_';
    if (ch != '_' || out.empty() || out.back() != '_') out += ch;
  }
  return out;
}

// Embree ms ÷ approximation ms: above 1 the approximation is faster.
double speedup(double reference_ms, double ms) { return reference_ms / ms; }

// The settings of `p`'s method other than the demo's at which it beats Embree.
std::string wins_at(const TechniquePoint& p, const std::vector<TechniquePoint>& points) {
  std::string list;
  for (const TechniquePoint& q : points)
    if (!q.demo && q.technique == p.technique && q.method == p.method && speedup(q.reference_ms, q.ms) >= 1.0)
      list += (list.empty() ? "" : ", ") + q.knob + " " + format_cell(q.knob_value);
  return list.empty() ? std::string("–") : list;
}

// Error against ms of one technique's points: a column per method (its points in ms order)
// and one for Embree (error 0 at each distinct reference time).
Table curve_table(const std::string& technique, const std::vector<TechniquePoint>& points) {
  std::vector<std::string> methods;
  std::vector<double> embree;
  std::string unit;
  for (const TechniquePoint& p : points) {
    if (p.technique != technique) continue;
    if (std::find(methods.begin(), methods.end(), p.method) == methods.end()) methods.push_back(p.method);
    if (std::find(embree.begin(), embree.end(), p.reference_ms) == embree.end()) embree.push_back(p.reference_ms);
    unit = p.error_unit;
  }
  Table t{"Error vs ms: " + technique + " (" + unit + ")", {"method", "setting", "ms"}, {}};
  for (const std::string& m : methods) t.columns.push_back(m);
  t.columns.push_back("Embree");
  const size_t n = t.columns.size();
  for (size_t k = 0; k < methods.size(); ++k) {
    std::vector<const TechniquePoint*> mine;
    for (const TechniquePoint& p : points)
      if (p.technique == technique && p.method == methods[k]) mine.push_back(&p);
    std::sort(mine.begin(), mine.end(), [](auto* a, auto* b) { return a->ms < b->ms; });
    for (const TechniquePoint* p : mine) {
      std::vector<std::variant<std::string, double>> row(n, kNaN);
      row[0] = methods[k];
      row[1] = p->knob + " " + format_cell(p->knob_value) + (p->demo ? " (demo)" : "");
      row[2] = p->ms;
      row[3 + k] = p->error;
      t.rows.push_back(std::move(row));
    }
  }
  std::sort(embree.begin(), embree.end());
  for (double ms : embree) {
    std::vector<std::variant<std::string, double>> row(n, kNaN);
    row[0] = std::string("Embree");
    row[1] = std::string("exact");
    row[2] = ms;
    row[n - 1] = 0.0;
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace

Results technique_bench_results(const std::vector<TechniquePoint>& points) {
  Results r;
  Table ratios{"Techniques vs Embree at the demo's settings (ratio = Embree ms ÷ technique ms; > 1 = faster)",
               {"technique", "method", "ms", "Embree ms", "ratio", "preparation ms", "Embree BVH ms",
                "ratio with preparation", "error", "error unit", "faster than Embree at"},
               {}};
  for (const TechniquePoint& p : points) {
    if (!p.demo) continue;
    const double s = speedup(p.reference_ms, p.ms);
    const double with = speedup(p.reference_ms + p.reference_build_ms, p.ms + p.approximation_build_ms);
    ratios.rows.push_back({p.technique, p.method, p.ms, p.reference_ms, s, p.approximation_build_ms,
                           p.reference_build_ms, with, p.error, p.error_unit,
                           s >= 1.0 ? std::string("the demo's setting") : wins_at(p, points)});
    const std::string n = metric_name(p);
    r.metrics[n + "_ratio"] = s;
    r.metrics[n + "_ms"] = p.ms;
    r.metrics[n + "_embree_ms"] = p.reference_ms;
    r.metrics[n + "_error"] = p.error;
  }
  Section section{"bench", "Techniques vs Embree: time and error",
                  "Each technique and its Embree reference timed side by side in the same run (same "
                  "threads, same rays or views), medians over interleaved repetitions. The ratio is "
                  "Embree's time over the technique's: below 1 the technique is slower than exact ray "
                  "tracing on this CPU. Preparation is the per-scene or per-frame work outside the "
                  "technique's frame time (cube-map builds, depth images and their meshes, the BSP); "
                  "Embree's BVH build is shown where it was timed (0 = not timed). The last column "
                  "lists the other measured settings at which the technique beats Embree. The plots "
                  "show error against milliseconds for each setting measured, beside Embree's point "
                  "(error 0). The cluster plot also shows the engines' baseline, screen-space "
                  "reflections with the box-probe fallback (ssr), on the same frames and rays: its ms "
                  "holds the G-buffer step, its depth, back-face and pyramid passes, the walk and the "
                  "fallback lookups; the fallback's cube-map build is its preparation.",
                  {ratios.title}, {}, {"proxima bench techniques"}};
  r.tables.push_back(ratios);
  for (const std::string& t : technique_bench_names()) {
    if (std::none_of(points.begin(), points.end(), [&](const TechniquePoint& p) { return p.technique == t; }))
      continue;
    Table curve = curve_table(t, points);
    PlotSpec plot{"Error vs ms: " + t, curve.title, "line", "ms",
                  std::vector<std::string>(curve.columns.begin() + 3, curve.columns.end()), "ms", "error"};
    section.tables.push_back(curve.title);
    section.plots.push_back(std::move(plot));
    r.tables.push_back(std::move(curve));
  }
  r.sections.push_back(std::move(section));
  return r;
}

Results run_technique_bench(const Scene& /*scene*/, const TechniqueBenchOptions& options, const StudyOutput& /*out*/,
                            Progress* progress) {
  return technique_bench_results(measure_techniques(options, true, progress));
}

}  // namespace proxima::study
