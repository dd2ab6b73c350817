// `proxima sample`: sample a scene with n depth images (conventional, depth peeling, NRR
// with pixel or visibility redundancy; thesis ch. 2) and measure the four sampling
// metrics against K intermediate output frames (docs/depthimage.md).
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/timer.h"
#include "proxima/depthimage/sampling_metrics.h"
#include "proxima/scene/load.h"

namespace proxima::cli {

namespace {

enum class Method { Conventional, Peeling, NrrPixel, NrrVisibility };

struct MethodInfo {
  Method method;
  const char* name;    // flag value
  const char* metric;  // metric prefix when several methods run
};

constexpr MethodInfo kMethods[] = {
    {Method::Conventional, "conventional", "conventional_"},
    {Method::Peeling, "peeling", "peeling_"},
    {Method::NrrPixel, "nrr-pixel", "nrr_pixel_"},
    {Method::NrrVisibility, "nrr-visibility", "nrr_visibility_"},
};

const MethodInfo& method_info(const std::string& name) {
  for (const MethodInfo& m : kMethods)
    if (name == m.name) return m;
  fail_input("--method: unknown method '" + name + "' (conventional, peeling, nrr-pixel, nrr-visibility)");
}

struct SampleFlags {
  CommonOptions common;
  CameraChoice camera;
  std::vector<std::string> methods{"nrr-pixel"};
  std::string views = "triangle";
  std::string redundancy;  // empty: the NRR method's own
  int frames = 1000;
  float radius = 0.0f;  // 0: 8 % of the distance to the target
  int reps = 3;
  bool no_images = false;
};

// Triangle ids as float for EXR (exact up to 2^24; −1 where empty).
ImageF ids_as_float(const ImageU32& ids) {
  ImageF out(ids.width(), ids.height(), 1);
  for (size_t i = 0; i < ids.data().size(); ++i)
    out.data()[i] = ids.data()[i] == kNoTriangle ? -1.0f : float(ids.data()[i]);
  return out;
}

// Thesis Table 3 colours over a dimmed grey copy of the image: occluded green, occluded
// and useful yellow.
ImageF classes_image(const DepthImage& image, const ImageU8& classes) {
  ImageF out(image.color.width(), image.color.height(), 3);
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      const uint8_t c = classes.at(x, y);
      const float grey = 0.3f * (image.color.at(x, y, 0) + image.color.at(x, y, 1) + image.color.at(x, y, 2)) / 3.0f;
      const vec3 rgb = c == 2 ? vec3(1, 1, 0) : c == 1 ? vec3(0, 1, 0) : vec3(grey);
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = rgb[k];
    }
  }
  return out;
}

std::string pct_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f%%", v);
  return buf;
}

}  // namespace

Command register_sample(CLI::App& root) {
  static SampleFlags f;
  auto* app = root.add_subcommand("sample", "sample a scene with depth images (conventional, peeling, NRR) and "
                                            "measure redundant / occluded / useful / available samples");
  add_scene_flag(app, f.common, "nest");
  add_camera_flags(app, f.camera);
  f.common.width = f.common.height = 1024;
  add_size_flags(app, f.common);  // --height defaults to --width (the thesis' images are square)
  add_threads_flag(app, f.common);
  add_seed_flag(app, f.common);
  add_out_flag(app, f.common, true);
  app->add_option("--method", f.methods,
                  "conventional|peeling|nrr-pixel|nrr-visibility; several, comma-separated, share the output frames")
      ->delimiter(',')
      ->capture_default_str();
  app->add_option("--views", f.views, "view set: segment (2 views), triangle (3), rectangle (4)")->capture_default_str();
  app->add_option("--redundancy", f.redundancy,
                  "pixel|visibility: definition the metrics use (default: visibility for nrr-visibility alone, else pixel)");
  app->add_option("--frames", f.frames, "K intermediate output frames for the useful / available metrics")
      ->capture_default_str();
  app->add_option("--radius", f.radius, "distance of the views from the scene camera, m (0 = 8 % of the focus distance)")
      ->capture_default_str();
  app->add_option("--reps", f.reps, "timed repetitions of each method (median reported)")->capture_default_str();
  app->add_flag("--no-images", f.no_images, "write results.json only, no per-image files");

  return {app, [app] {
            if (app->count("--height") == 0) f.common.height = f.common.width;
            // Check every input before the output directory exists.
            if (f.common.threads < 0) fail_input("--threads: must be ≥ 0");
            if (f.frames < 0 || f.frames > 100000) fail_input("--frames: must be in 0..100000");
            if (f.reps < 1 || f.reps > 100) fail_input("--reps: must be in 1..100");
            if (!(f.radius >= 0.0f) || f.radius > 1e6f) fail_input("--radius: must be ≥ 0 (and finite)");
            std::vector<MethodInfo> methods;
            for (const std::string& m : f.methods) methods.push_back(method_info(m));
            if (methods.empty()) fail_input("--method: give at least one method");
            const ViewShape shape = parse_view_shape(f.views, "--views");
            auto uses = [&](Method m) {
              return std::any_of(methods.begin(), methods.end(), [&](const MethodInfo& i) { return i.method == m; });
            };
            Redundancy redundancy = uses(Method::NrrVisibility) && !uses(Method::NrrPixel) ? Redundancy::Visibility
                                                                                           : Redundancy::Pixel;
            if (f.redundancy == "visibility") redundancy = Redundancy::Visibility;
            else if (f.redundancy == "pixel") redundancy = Redundancy::Pixel;
            else if (!f.redundancy.empty()) fail_input("--redundancy: must be pixel or visibility");

            ThreadLimit limit(f.common.threads);
            Scene scene = load_scene(f.common.scene);
            const Camera base = pick_camera(scene, f.camera, f.common.width, f.common.height);
            const float focus = std::max(1e-3f, glm::length(scene_bounds(scene).center() - base.position));
            const ViewSet set = make_view_set(shape, base, f.radius > 0.0f ? f.radius : 0.08f * focus, focus);
            const auto out = prepare_out_dir(f.common.out);

            Results results;
            results.command = command_line();
            results.threads = active_threads();
            const RayScene rays(scene);
            std::vector<Camera> cameras;
            for (size_t i = 0; i < set.corners.size(); ++i) cameras.push_back(corner_camera(set, i));
            const Camera centroid = centroid_camera(set);
            const int n = int(cameras.size());

            // Sample with every method, timed side by side (median of --reps).
            auto run = [&](Method m) {
              switch (m) {
                case Method::Conventional: return sample_conventional(scene, cameras, true);
                case Method::Peeling: return sample_peeling(scene, centroid, n, true);
                case Method::NrrPixel: return sample_nrr(scene, cameras, Redundancy::Pixel, &rays, true);
                case Method::NrrVisibility: return sample_nrr(scene, cameras, Redundancy::Visibility, &rays, true);
              }
              return std::vector<DepthImage>{};
            };
            std::vector<std::vector<DepthImage>> sets(methods.size());
            std::vector<std::vector<double>> times(methods.size());
            for (int r = 0; r < f.reps; ++r) {
              for (size_t k = 0; k < methods.size(); ++k) {
                Stopwatch watch;
                sets[k] = run(methods[k].method);
                times[k].push_back(watch.elapsed_ms());
              }
            }
            const std::vector<DepthImage> conventional = sample_conventional(scene, cameras, false);

            MetricsOptions options;
            options.redundancy = redundancy;
            options.frames = f.frames;
            options.seed = f.common.seed;
            SampleClasses classes;
            Stopwatch metrics_watch;
            const std::vector<SamplingMetrics> metrics =
                measure_sampling(scene, rays, set, sets, conventional, options, &classes);
            const double metrics_ms = metrics_watch.elapsed_ms();

            const bool prefixed = methods.size() > 1;
            const std::string def = redundancy_name(redundancy);
            std::vector<std::string> view_columns{"method"};
            for (int i = 0; i < n; ++i) view_columns.push_back("V" + std::to_string(i) + " image");
            Table table2{"Sampling metrics, " + def + " redundancy: " + scene.name +
                             " (conventional: redundant samples; others: occluded (useful) samples)",
                         view_columns, {}};
            Table detail{"Per image: " + scene.name + ", " + def + " redundancy, K = " + std::to_string(f.frames),
                         {"method", "image", "samples", "redundant_pct", "occluded_pct", "useful_pct"}, {}};
            std::vector<std::string> avail_columns{"scene"};
            std::vector<std::variant<std::string, double>> avail_row{scene.name};
            Table timing{"Sampling time: " + scene.name + ", " + std::to_string(n) + " images of " +
                             std::to_string(base.width) + "x" + std::to_string(base.height) + ", median of " +
                             std::to_string(f.reps),
                         {"method", "time_ms"}, {}};
            for (size_t k = 0; k < methods.size(); ++k) {
              const MethodInfo& info = methods[k];
              const SamplingMetrics& m = metrics[k];
              const std::string p = prefixed ? info.metric : "";
              std::vector<std::variant<std::string, double>> row{info.name};
              for (int i = 0; i < n; ++i) {
                results.metrics[p + "redundant_pct_" + std::to_string(i)] = m.redundant_pct[size_t(i)];
                results.metrics[p + "occluded_pct_" + std::to_string(i)] = m.occluded_pct[size_t(i)];
                results.metrics[p + "useful_pct_" + std::to_string(i)] = m.useful_pct[size_t(i)];
                row.push_back(info.method == Method::Conventional
                                  ? pct_text(m.redundant_pct[size_t(i)])
                                  : pct_text(m.occluded_pct[size_t(i)]) + " (" + pct_text(m.useful_pct[size_t(i)]) + ")");
                detail.rows.push_back({info.name, double(i), double(m.samples[size_t(i)]), m.redundant_pct[size_t(i)],
                                       m.occluded_pct[size_t(i)], m.useful_pct[size_t(i)]});
              }
              table2.rows.push_back(row);
              results.metrics[p + "available_avg_pct"] = m.available_avg_pct;
              results.metrics[p + "available_min_pct"] = m.available_min_pct;
              avail_columns.push_back(std::string(info.name) + " avg");
              avail_columns.push_back(std::string(info.name) + " min");
              avail_row.push_back(m.available_avg_pct);
              avail_row.push_back(m.available_min_pct);
              const double t = median(times[k]);
              results.metrics[p + "time_ms"] = t;
              timing.rows.push_back({info.name, t});

              if (f.no_images) continue;
              for (int i = 0; i < n; ++i) {
                const DepthImage& image = sets[k][size_t(i)];
                const std::string stem = std::string(info.name) + "_" + std::to_string(i);
                write_png_linear(out / (stem + "_color.png"), image.color);
                write_exr(out / (stem + "_depth.exr"), image.depth);
                write_exr(out / (stem + "_id.exr"), ids_as_float(image.triangle));
                write_png_linear(out / (stem + "_occluded.png"), classes_image(image, classes[k][size_t(i)]));
                results.images[stem + "_color"] = stem + "_color.png";
                results.images[stem + "_depth"] = stem + "_depth.exr";
                results.images[stem + "_id"] = stem + "_id.exr";
                results.images[stem + "_occluded"] = stem + "_occluded.png";
              }
            }
            results.metrics["metrics_ms"] = metrics_ms;
            results.metrics["triangles"] = double(scene.triangles.size());
            results.metrics["frames"] = double(f.frames);
            results.tables.push_back(table2);
            results.tables.push_back({"Available samples per output frame, " + def + " redundancy, %",
                                      avail_columns, {avail_row}});
            results.tables.push_back(detail);
            results.tables.push_back(timing);
            publish_results(out, results);
            return 0;
          }};
}

}  // namespace proxima::cli
