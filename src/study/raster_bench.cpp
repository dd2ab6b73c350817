#include "proxima/study/raster_bench.h"

#include <algorithm>
#include <string>

#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
#include "proxima/raster/raster_bench.h"

namespace proxima::study {

namespace {

void add_agreement(Results& results) {
  const AgreementSummary s = agreement_summary(512);
  Table agree{"rasterized vs ray-cast triangle ids, 512×512, every built-in camera",
              {"scene", "camera", "agreement_pct", "edge", "on_shared_edge", "depth_tie", "other"},
              {}};
  for (const CameraAgreement& c : s.cameras) {
    const IdAgreement& a = c.agreement;
    agree.rows.push_back({c.scene, c.camera, a.agreement_pct(), double(a.edge), double(a.on_shared_edge),
                          double(a.depth), double(a.other)});
  }
  results.metrics["id_agreement_pct"] = s.min_agreement_pct;
  results.metrics["id_agreement_with_ties_pct"] = s.min_with_ties_pct;
  results.metrics["id_disagreements_other"] = double(s.other);
  results.tables.push_back(agree);
}

}  // namespace

void validate(const RasterBenchStudyOptions& o) {
  require_in_range(o.reps, 1, 1000, "--reps");
}

AgreementSummary agreement_summary(int size) {
  AgreementSummary s;
  s.cameras = raster_agreement_on_builtins(size);
  for (const CameraAgreement& c : s.cameras) {
    s.min_agreement_pct = std::min(s.min_agreement_pct, c.agreement.agreement_pct());
    s.min_with_ties_pct = std::min(s.min_with_ties_pct, c.agreement.agreement_with_ties_pct());
    s.other += c.agreement.other;
  }
  return s;
}

Results run_raster_bench(const Scene& scene, const RasterBenchStudyOptions& options, const StudyOutput& /*out*/,
                         Progress* /*progress*/) {
  validate(options);
  const Camera cam = pick_camera(scene, options.camera, options.width, options.height);
  const int all = options.threads > 0 ? options.threads : hardware_threads();
  Results results;
  if (!options.skip_agreement) add_agreement(results);

  // Speed: at 1 and all threads, one run.
  RasterBenchOptions opts;
  opts.threads = all == 1 ? std::vector<int>{1} : std::vector<int>{1, all};
  opts.repetitions = options.reps;
  const std::vector<RasterTiming> timings = bench_raster(scene, cam, opts);
  Table speed{"raster " + scene.name + ", " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                  ", median of " + std::to_string(options.reps),
              {"threads", "depth_id_ms", "gbuffer_ms", "tris_per_s"},
              {}};
  for (const RasterTiming& t : timings) {
    speed.rows.push_back({double(t.threads), t.depth_id_ms, t.gbuffer_ms, t.tris_per_s});
    const std::string suffix = t.threads == all ? "" : "_1t";
    results.metrics["raster_ms_depth_id" + suffix] = t.depth_id_ms;
    results.metrics["raster_ms_gbuffer" + suffix] = t.gbuffer_ms;
    results.metrics["tris_per_s" + suffix] = t.tris_per_s;
  }
  results.tables.push_back(speed);
  return results;
}

}  // namespace proxima::study
