#include "proxima/study/raster_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/raster/raster_bench.h"

namespace proxima::study {

namespace {

// Runs the llvmpipe harness; NaN (and the reason in *why) when it is absent or fails.
double llvmpipe_ms(const RasterBenchStudyOptions& o, int width, int height, int threads, std::string* why) {
  namespace fs = std::filesystem;
  if (o.llvmpipe_harness.empty() || !fs::exists(o.llvmpipe_harness)) {
    *why = "llvmpipe harness not built (needs libegl-dev libgl-dev)";
    return std::nan("");
  }
  std::string cmd = o.llvmpipe_harness.string() + " --scene " + o.llvmpipe_scene + " --width " +
                    std::to_string(width) + " --height " + std::to_string(height) + " --threads " +
                    std::to_string(threads) + " --repetitions " + std::to_string(o.reps);
  if (!o.camera.camera.empty()) cmd += " --camera " + o.camera.camera;
  FILE* pipe = popen((cmd + " 2>/dev/null").c_str(), "r");
  if (!pipe) {
    *why = "cannot start the llvmpipe harness";
    return std::nan("");
  }
  std::string text;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) text.append(buf, n);
  const int status = pclose(pipe);
  if (status != 0) {
    *why = "llvmpipe harness failed (exit status " + std::to_string(status) + "; EGL/llvmpipe unavailable?)";
    return std::nan("");
  }
  try {
    return nlohmann::json::parse(text).at("ms_depth_id").get<double>();
  } catch (const std::exception& e) {
    *why = std::string("llvmpipe harness printed unreadable output: ") + e.what();
    return std::nan("");
  }
}

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
  if (o.reps < 1 || o.reps > 1000) fail_input("--reps: must be in 1..1000");
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

  // Speed: proxima at 1 and all threads, llvmpipe at the same counts, one run.
  RasterBenchOptions opts;
  opts.threads = all == 1 ? std::vector<int>{1} : std::vector<int>{1, all};
  opts.repetitions = options.reps;
  const std::vector<RasterTiming> timings = bench_raster(scene, cam, opts);
  Table speed{"raster " + scene.name + ", " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                  ", median of " + std::to_string(options.reps),
              {"threads", "depth_id_ms", "gbuffer_ms", "tris_per_s", "llvmpipe_depth_id_ms", "speedup_vs_llvmpipe"},
              {}};
  std::string why;
  for (const RasterTiming& t : timings) {
    const double gl = llvmpipe_ms(options, cam.width, cam.height, t.threads, &why);
    const double speedup = gl / t.depth_id_ms;
    speed.rows.push_back({double(t.threads), t.depth_id_ms, t.gbuffer_ms, t.tris_per_s, gl, speedup});
    const std::string suffix = t.threads == all ? "" : "_1t";
    results.metrics["raster_ms_depth_id" + suffix] = t.depth_id_ms;
    results.metrics["raster_ms_gbuffer" + suffix] = t.gbuffer_ms;
    results.metrics["tris_per_s" + suffix] = t.tris_per_s;
    results.metrics["llvmpipe_ms_depth_id" + suffix] = gl;
    results.metrics["speedup_vs_llvmpipe" + suffix] = speedup;
  }
  if (!why.empty()) std::fprintf(stderr, "proxima: bench raster: %s; llvmpipe columns left empty\n", why.c_str());
  results.tables.push_back(speed);
  return results;
}

}  // namespace proxima::study
