// `proxima bench trace`: BVH build time and rays per second of the Embree reference on a
// built-in scene, at 1 thread and at all threads, medians over repetitions.
// `proxima bench raster`: the software rasterizer's agreement with Embree item buffers on
// every built-in camera, and its frame time on living-room beside Mesa's llvmpipe
// (the optional harness proxima_llvmpipe_bench next to this binary), in one run.
#include <cstdio>
#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/eval/raster_agreement.h"
#include "proxima/scene/load.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::cli {

namespace {

struct BenchFlags {
  CommonOptions common;
  CameraChoice camera;
  int reps = 5;
  bool skip_agreement = false;
};

std::vector<Ray> primary_rays(const Camera& cam) {
  std::vector<Ray> rays(size_t(cam.width) * size_t(cam.height));
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      rays[size_t(y) * size_t(cam.width) + size_t(x)] = ray_through(cam, {float(x) + 0.5f, float(y) + 0.5f});
  return rays;
}

// Mirror rays from every primary hit on a reflective surface (what reflections cost).
std::vector<Ray> reflection_rays(const Scene& scene, std::span<const Ray> primary, std::span<const Hit> hits) {
  float eps = 1e-4f * std::max(1.0f, scene_bounds(scene).diagonal());
  std::vector<Ray> rays;
  for (size_t i = 0; i < hits.size(); ++i) {
    const Hit& h = hits[i];
    if (!h.valid() || !scene.materials[scene.triangle_material[h.triangle]].reflective()) continue;
    vec3 n = shading_normal(scene, h.triangle, h.u, h.v);
    if (glm::dot(n, primary[i].dir) > 0.0f) n = -n;
    Ray r;
    r.origin = primary[i].origin + h.t * primary[i].dir;
    r.dir = glm::reflect(primary[i].dir, n);
    r.tmin = eps;
    rays.push_back(r);
  }
  return rays;
}

// Median rays per second (millions) of batched closest-hit queries.
double median_mrays(const RayScene& rs, std::span<const Ray> rays, int reps) {
  std::vector<Hit> hits(rays.size());
  rs.intersect(rays, hits);  // warm-up
  std::vector<double> ms;
  for (int i = 0; i < reps; ++i) {
    Stopwatch w;
    rs.intersect(rays, hits);
    ms.push_back(w.elapsed_ms());
  }
  return double(rays.size()) / (median(ms) * 1e3);
}

int run_trace(const BenchFlags& f) {
  if (f.reps < 1 || f.reps > 1000) fail_input("--reps: must be in 1..1000");
  Scene scene = load_scene(f.common.scene);
  Camera cam = pick_camera(scene, f.camera, f.common.width, f.common.height);
  auto out = prepare_out_dir(f.common.out);
  int all = f.common.threads > 0 ? f.common.threads : hardware_threads();

  Results results;
  results.command = command_line();
  results.threads = all;
  std::vector<Ray> primary = primary_rays(cam);
  std::vector<Hit> hits(primary.size());
  std::vector<Ray> reflected;
  Table table{"bench trace: " + scene.name + ", " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                  ", median of " + std::to_string(f.reps),
              {"threads", "bvh_build_ms", "primary_mrays_s", "reflection_mrays_s"},
              {}};
  for (int threads : {1, all}) {
    ThreadLimit limit(threads);
    std::vector<double> build;
    std::unique_ptr<RayScene> rs;
    for (int i = 0; i < f.reps; ++i) {
      rs = std::make_unique<RayScene>(scene);
      build.push_back(rs->build_ms());
    }
    if (reflected.empty()) {
      rs->intersect(primary, hits);
      reflected = reflection_rays(scene, primary, hits);
    }
    double p = median_mrays(*rs, primary, f.reps);
    double r = reflected.empty() ? 0.0 : median_mrays(*rs, reflected, f.reps);
    std::string suffix = threads == all ? "" : "_1t";
    results.metrics["bvh_build_ms" + suffix] = median(build);
    results.metrics["primary_mrays_s" + suffix] = p;
    results.metrics["reflection_mrays_s" + suffix] = r;
    table.rows.push_back({double(threads), median(build), p, r});
    if (threads == all) break;  // all == 1 on a single-core machine
  }
  results.metrics["reflection_rays"] = double(reflected.size());
  results.metrics["triangles"] = double(scene.triangles.size());
  results.tables.push_back(table);
  publish_results(out, results);
  return 0;
}

// Runs the llvmpipe harness beside this executable; NaN when it is absent or fails.
double llvmpipe_ms(const std::string& scene, const CameraChoice& camera, int width, int height, int threads,
                   int reps, std::string* why) {
  namespace fs = std::filesystem;
  fs::path self = fs::read_symlink("/proc/self/exe");
  fs::path harness = self.parent_path() / "proxima_llvmpipe_bench";
  if (!fs::exists(harness)) {
    *why = "llvmpipe harness not built (needs libegl-dev libgl-dev)";
    return std::nan("");
  }
  std::string cmd = harness.string() + " --scene " + scene + " --width " + std::to_string(width) + " --height " +
                    std::to_string(height) + " --threads " + std::to_string(threads) + " --repetitions " +
                    std::to_string(reps);
  if (!camera.camera.empty()) cmd += " --camera " + camera.camera;
  FILE* pipe = popen((cmd + " 2>/dev/null").c_str(), "r");
  if (!pipe) {
    *why = "cannot start the llvmpipe harness";
    return std::nan("");
  }
  std::string text;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) text.append(buf, n);
  int status = pclose(pipe);
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

int run_raster(const BenchFlags& f) {
  if (f.reps < 1 || f.reps > 1000) fail_input("--reps: must be in 1..1000");
  Scene scene = load_scene(f.common.scene);
  Camera cam = pick_camera(scene, f.camera, f.common.width, f.common.height);
  auto out = prepare_out_dir(f.common.out);
  int all = f.common.threads > 0 ? f.common.threads : hardware_threads();

  Results results;
  results.command = command_line();
  results.threads = all;

  // Agreement with Embree: every built-in scene, every camera, 512×512.
  Table agree{"rasterized vs ray-cast triangle ids, 512×512, every built-in camera",
              {"scene", "camera", "agreement_pct", "edge", "on_shared_edge", "depth_tie", "other"},
              {}};
  double min_agreement = 100.0, min_with_ties = 100.0;
  size_t other_total = 0;
  if (!f.skip_agreement) {
    for (const CameraAgreement& c : raster_agreement_on_builtins(512)) {
      const IdAgreement& a = c.agreement;
      min_agreement = std::min(min_agreement, a.agreement_pct());
      min_with_ties = std::min(min_with_ties, a.agreement_with_ties_pct());
      other_total += a.other;
      agree.rows.push_back({c.scene, c.camera, a.agreement_pct(), double(a.edge), double(a.on_shared_edge),
                            double(a.depth), double(a.other)});
    }
    results.metrics["id_agreement_pct"] = min_agreement;
    results.metrics["id_agreement_with_ties_pct"] = min_with_ties;
    results.metrics["id_disagreements_other"] = double(other_total);
    results.tables.push_back(agree);
  }

  // Speed: proxima at 1 and all threads, llvmpipe at the same counts, one run.
  RasterBenchOptions opts;
  opts.threads = all == 1 ? std::vector<int>{1} : std::vector<int>{1, all};
  opts.repetitions = f.reps;
  std::vector<RasterTiming> timings = bench_raster(scene, cam, opts);
  Table speed{"raster " + scene.name + ", " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                  ", median of " + std::to_string(f.reps),
              {"threads", "depth_id_ms", "gbuffer_ms", "tris_per_s", "llvmpipe_depth_id_ms", "speedup_vs_llvmpipe"},
              {}};
  std::string why;
  for (const RasterTiming& t : timings) {
    double gl = llvmpipe_ms(f.common.scene, f.camera, cam.width, cam.height, t.threads, f.reps, &why);
    double speedup = gl / t.depth_id_ms;
    speed.rows.push_back({double(t.threads), t.depth_id_ms, t.gbuffer_ms, t.tris_per_s, gl, speedup});
    std::string suffix = t.threads == all ? "" : "_1t";
    results.metrics["raster_ms_depth_id" + suffix] = t.depth_id_ms;
    results.metrics["raster_ms_gbuffer" + suffix] = t.gbuffer_ms;
    results.metrics["tris_per_s" + suffix] = t.tris_per_s;
    results.metrics["llvmpipe_ms_depth_id" + suffix] = gl;
    results.metrics["speedup_vs_llvmpipe" + suffix] = speedup;
  }
  if (!why.empty()) std::fprintf(stderr, "proxima: bench raster: %s; llvmpipe columns left empty\n", why.c_str());
  results.tables.push_back(speed);
  publish_results(out, results);
  return 0;
}

}  // namespace

Command register_bench(CLI::App& root) {
  static BenchFlags f;
  auto* app = root.add_subcommand("bench", "benchmarks (medians of repetitions, written to results.json)");
  app->require_subcommand(1);
  auto* trace = app->add_subcommand("trace", "Embree reference: BVH build, primary and reflection rays per second");
  add_scene_flag(trace, f.common, "living-room");
  add_camera_flags(trace, f.camera);
  f.common.width = 1024;
  f.common.height = 1024;
  add_size_flags(trace, f.common);
  add_threads_flag(trace, f.common);
  add_out_flag(trace, f.common, false);
  f.common.out = "out/bench-trace";
  trace->add_option("--reps", f.reps, "repetitions per measurement")->capture_default_str();

  static BenchFlags r;
  auto* raster = app->add_subcommand(
      "raster", "software rasterizer: id agreement with Embree on every built-in camera; ms/frame vs llvmpipe");
  add_scene_flag(raster, r.common, "living-room");
  add_camera_flags(raster, r.camera);
  r.common.width = 1024;
  r.common.height = 1024;
  add_size_flags(raster, r.common);
  add_threads_flag(raster, r.common);
  add_out_flag(raster, r.common, false);
  r.common.out = "out/bench-raster";
  r.reps = 9;
  raster->add_option("--reps", r.reps, "repetitions per measurement")->capture_default_str();
  raster->add_flag("--skip-agreement", r.skip_agreement, "time only; skip the Embree agreement pass");
  const Command view = register_bench_view(*app);
  return {app, [trace, raster, view] {
            if (trace->parsed()) return run_trace(f);
            if (raster->parsed()) return run_raster(r);
            if (view.app->parsed()) return view.run();
            return 2;
          }};
}

}  // namespace proxima::cli
