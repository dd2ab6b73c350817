// Demo section: every technique beside Embree, time against error (study/technique_bench.h,
// `proxima bench techniques`). The demo's own settings are those the sections before this
// one just ran: their timings are reused, not measured again; the other settings of each
// technique's knob are measured here once each.
#include <algorithm>
#include <string>
#include <vector>

#include "demo_sections.h"
#include "proxima/study/technique_bench.h"

namespace proxima::study::demo {

namespace {

// Where the earlier sections left each technique's demo-settings metrics (their prefixes).
struct Reuse {
  const char* technique;
  const char* where;
  const char* prefix;
  const char* knob;
  double knob_value;
  const char* probe;  // a metric the section writes (absent: the section did not run)
};
constexpr Reuse kReuse[] = {{"envmap", "room-reflector", "envmap_room-reflector_", "cube size", 256, "reference_ms"},
                            {"cluster", "living-room walk", "cluster_living-room_walk_", "resolution scale", 1, "reference_ms_avg"},
                            {"cluster", "bathroom walk", "cluster_bathroom_walk_", "resolution scale", 1, "reference_ms_avg"},
                            {"temporal", "living-room walk", "temporal_living-room_walk_", "key-frame threshold", 0.3, "reference_ms_avg"},
                            {"temporal", "bathroom walk", "temporal_bathroom_walk_", "key-frame threshold", 0.3, "reference_ms_avg"},
                            {"shadows", "city", "shadows_city_light_1_", "shadow-map side", 1024, "time_rays_ms"}};

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

}  // namespace

void bench_section(Context& c) {
  // Not a study run to hand out: its timings compare techniques on one machine, so a sweep
  // of the demo measures them when it merges (on rank 0), and planning lists nothing here.
  if (c.plan) return;
  c.progress->step("techniques vs Embree");
  std::vector<TechniquePoint> points;
  std::vector<std::string> reused;
  // Quick run: the sections' own figures at the demo's settings where they were run.
  for (const Reuse& u : kReuse) {
    const std::string pre = u.prefix;
    if (c.full || !c.results->metrics.count(pre + u.probe)) continue;  // --full: other settings there
    auto m = [&](const std::string& name) { return metric(*c.results, pre + name); };
    for (TechniquePoint& p : technique_points(u.technique, u.where, u.knob, u.knob_value, true, m))
      points.push_back(std::move(p));
    if (reused.empty() || reused.back() != u.technique) reused.push_back(u.technique);
  }
  std::vector<std::string> measured;
  for (const std::string& t : technique_bench_names())
    if (std::find(reused.begin(), reused.end(), t) == reused.end()) measured.push_back(t);
  TechniqueBenchOptions o;
  o.reps = c.full ? 5 : 1;
  o.seed = c.seed;
  o.sweep = false;
  if (!measured.empty()) {
    o.techniques = join(measured);
    for (TechniquePoint& p : measure_techniques(o, true)) points.push_back(std::move(p));
  }
  o.techniques = "all";
  o.sweep = true;
  for (TechniquePoint& p : measure_techniques(o, false)) points.push_back(std::move(p));

  Results r = technique_bench_results(points);
  for (auto& [name, value] : r.metrics) c.results->metrics["bench_" + name] = value;
  for (Table& t : r.tables) c.results->tables.push_back(std::move(t));
  Section section = std::move(r.sections.front());
  section.text += "\n\nThis run: " +
                  (reused.empty() ? std::string("every point measured here")
                                  : "the demo's settings of " + join(reused) +
                                        " are the figures of their sections above (their medians); the other points "
                                        "were measured here") +
                  ", " + std::to_string(o.reps) + " repetition" + (o.reps > 1 ? "s" : "") +
                  " each. On a shared machine single repetitions are noisy: `proxima bench techniques` "
                  "runs every point 5 times, interleaved.";
  section.commands = {"proxima bench techniques --threads " + std::to_string(c.threads)};
  c.results->sections.push_back(std::move(section));
}

}  // namespace proxima::study::demo
