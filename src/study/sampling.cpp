// The depth-image sampling study (thesis ch. 2, Algorithms 1–3 and the metrics of §2.3.2;
// docs/depthimage.md): the view set V_0 … V_{n−1} around the chosen camera, every method's
// n images timed side by side, the metrics of all methods against one set of K frames.
#include "proxima/study/sampling.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <variant>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/range_check.h"
#include "proxima/core/timer.h"
#include "proxima/depthimage/sampling_metrics.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::study {

namespace {

constexpr SamplingMethod kMethods[] = {SamplingMethod::Conventional, SamplingMethod::Peeling,
                                       SamplingMethod::NrrPixel, SamplingMethod::NrrVisibility};

// Metric prefix of a method when several run.
std::string metric_prefix(SamplingMethod m) {
  std::string p = sampling_method_name(m);
  std::replace(p.begin(), p.end(), '-', '_');
  return p + "_";
}

bool uses(const SamplingOptions& o, SamplingMethod m) {
  return std::find(o.methods.begin(), o.methods.end(), m) != o.methods.end();
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

// The cameras of the view set: the corners V_i, and the centroid depth peeling uses.
std::vector<DepthImage> sample(const Scene& scene, const RayScene& rays, const SamplingViews& v, SamplingMethod m) {
  switch (m) {
    case SamplingMethod::Conventional: return sample_conventional(scene, v.corners, true);
    case SamplingMethod::Peeling: return sample_peeling(scene, v.centroid, int(v.corners.size()), true);
    case SamplingMethod::NrrPixel: return sample_nrr(scene, v.corners, Redundancy::Pixel, &rays, true);
    case SamplingMethod::NrrVisibility: return sample_nrr(scene, v.corners, Redundancy::Visibility, &rays, true);
  }
  return {};
}

// The four tables, filled method by method.
struct Tables {
  Table metrics, available, detail, timing;
  std::vector<std::variant<std::string, double>> available_row;
};

Tables make_tables(const Scene& scene, const SamplingOptions& o, const SamplingViews& v) {
  const std::string def = redundancy_name(metric_redundancy(o));
  const int n = int(v.corners.size());
  std::vector<std::string> view_columns{"method"};
  for (int i = 0; i < n; ++i) view_columns.push_back("V" + std::to_string(i) + " image");
  Tables t;
  t.metrics = {"Sampling metrics, " + def + " redundancy: " + scene.name +
                   " (conventional: redundant samples; others: occluded (useful) samples)",
               view_columns, {}};
  t.available = {"Available samples per output frame, " + def + " redundancy, %", {"scene"}, {}};
  t.detail = {"Per image: " + scene.name + ", " + def + " redundancy, K = " + std::to_string(o.frames),
              {"method", "image", "samples", "redundant_pct", "occluded_pct", "useful_pct"}, {}};
  t.timing = {"Sampling time: " + scene.name + ", " + std::to_string(n) + " images of " +
                  std::to_string(v.set.base.width) + "x" + std::to_string(v.set.base.height) + ", median of " +
                  std::to_string(o.reps),
              {"method", "time_ms"}, {}};
  t.available_row = {scene.name};
  return t;
}

// One method's metrics, table rows and median time.
void add_method(Results& results, Tables& t, SamplingMethod m, const SamplingMetrics& metrics, double time_ms,
                const std::string& prefix) {
  const std::string name = sampling_method_name(m);
  std::vector<std::variant<std::string, double>> row{name};
  for (size_t i = 0; i < metrics.samples.size(); ++i) {
    const std::string index = std::to_string(i);
    results.metrics[prefix + "redundant_pct_" + index] = metrics.redundant_pct[i];
    results.metrics[prefix + "occluded_pct_" + index] = metrics.occluded_pct[i];
    results.metrics[prefix + "useful_pct_" + index] = metrics.useful_pct[i];
    row.push_back(m == SamplingMethod::Conventional
                      ? pct_text(metrics.redundant_pct[i])
                      : pct_text(metrics.occluded_pct[i]) + " (" + pct_text(metrics.useful_pct[i]) + ")");
    t.detail.rows.push_back({name, double(i), double(metrics.samples[i]), metrics.redundant_pct[i],
                             metrics.occluded_pct[i], metrics.useful_pct[i]});
  }
  t.metrics.rows.push_back(row);
  results.metrics[prefix + "available_avg_pct"] = metrics.available_avg_pct;
  results.metrics[prefix + "available_min_pct"] = metrics.available_min_pct;
  t.available.columns.push_back(name + " avg");
  t.available.columns.push_back(name + " min");
  t.available_row.push_back(metrics.available_avg_pct);
  t.available_row.push_back(metrics.available_min_pct);
  results.metrics[prefix + "time_ms"] = time_ms;
  t.timing.rows.push_back({name, time_ms});
}

// Colour, depth, triangle ids and the Table 3 classes of one method's images.
void write_images(const StudyOutput& out, Results& results, SamplingMethod m, const std::vector<DepthImage>& images,
                  const std::vector<ImageU8>& classes) {
  if (!out.wants_images()) return;
  for (size_t i = 0; i < images.size(); ++i) {
    const std::string stem = std::string(sampling_method_name(m)) + "_" + std::to_string(i);
    write_image(out, results, stem + "_color", stem + "_color.png", images[i].color);
    write_exr_image(out, results, stem + "_depth", stem + "_depth.exr", images[i].depth);
    write_exr_image(out, results, stem + "_id", stem + "_id.exr", triangle_ids_as_float(images[i].triangle));
    write_image(out, results, stem + "_occluded", stem + "_occluded.png", classes_image(images[i], classes[i]));
  }
}

}  // namespace

SamplingViews sampling_views(const Scene& scene, const SamplingOptions& o) {
  const Camera base = pick_camera(scene, o.camera, o.width, o.height);
  const float focus = std::max(1e-3f, glm::length(scene_bounds(scene).center() - base.position));
  SamplingViews v;
  v.set = make_view_set(o.views, base, o.radius > 0.0f ? o.radius : 0.08f * focus, focus);
  for (size_t i = 0; i < v.set.corners.size(); ++i) v.corners.push_back(corner_camera(v.set, i));
  v.centroid = centroid_camera(v.set);
  return v;
}

const char* sampling_method_name(SamplingMethod m) {
  switch (m) {
    case SamplingMethod::Conventional: return "conventional";
    case SamplingMethod::Peeling: return "peeling";
    case SamplingMethod::NrrPixel: return "nrr-pixel";
    case SamplingMethod::NrrVisibility: return "nrr-visibility";
  }
  return "?";
}

SamplingMethod parse_sampling_method(const std::string& name, const char* flag) {
  for (SamplingMethod m : kMethods)
    if (name == sampling_method_name(m)) return m;
  fail_input(std::string(flag) + ": unknown method '" + name + "' (conventional, peeling, nrr-pixel, nrr-visibility)");
}

void validate(const SamplingOptions& o) {
  Camera size;  // the default camera is valid but for the size under test
  size.width = o.width;
  size.height = o.height;
  validate_camera(size, "--width/--height");
  require_in_range(o.frames, 0, 100000, "--frames");
  require_in_range(o.reps, 1, 100, "--reps");
  if (!(o.radius >= 0.0f) || o.radius > 1e6f) fail_input("--radius: must be ≥ 0 (and finite)");
  if (o.methods.empty()) fail_input("--method: give at least one method");
}

void validate(const SamplingOptions& options, const Scene& scene) {
  validate(options);
  pick_camera(scene, options.camera, options.width, options.height);
}

Redundancy metric_redundancy(const SamplingOptions& o) {
  if (o.redundancy) return *o.redundancy;
  return uses(o, SamplingMethod::NrrVisibility) && !uses(o, SamplingMethod::NrrPixel) ? Redundancy::Visibility
                                                                                     : Redundancy::Pixel;
}

Results run_sampling(const Scene& scene, const SamplingOptions& o, const StudyOutput& out, Progress*) {
  validate(o);
  const SamplingViews views = sampling_views(scene, o);
  const RayScene rays(scene);

  // Every method sampled, timed side by side (median of reps).
  const size_t methods = o.methods.size();
  std::vector<std::vector<DepthImage>> sets(methods);
  std::vector<std::vector<double>> times(methods);
  for (int r = 0; r < o.reps; ++r) {
    for (size_t k = 0; k < methods; ++k) {
      Stopwatch watch;
      sets[k] = sample(scene, rays, views, o.methods[k]);
      times[k].push_back(watch.elapsed_ms());
    }
  }
  const std::vector<DepthImage> conventional = sample_conventional(scene, views.corners, false);

  MetricsOptions mo;
  mo.redundancy = metric_redundancy(o);
  mo.frames = o.frames;
  mo.seed = o.seed;
  SampleClasses classes;
  Stopwatch metrics_watch;
  const std::vector<SamplingMetrics> metrics = measure_sampling(scene, rays, views.set, sets, conventional, mo, &classes);
  const double metrics_ms = metrics_watch.elapsed_ms();

  Results results;
  Tables t = make_tables(scene, o, views);
  for (size_t k = 0; k < methods; ++k) {
    add_method(results, t, o.methods[k], metrics[k], median(times[k]), methods > 1 ? metric_prefix(o.methods[k]) : "");
    write_images(out, results, o.methods[k], sets[k], classes[k]);
  }
  results.metrics["metrics_ms"] = metrics_ms;
  results.metrics["triangles"] = double(scene.triangles.size());
  results.metrics["frames"] = double(o.frames);
  t.available.rows.push_back(t.available_row);
  results.tables = {t.metrics, t.available, t.detail, t.timing};
  return results;
}

}  // namespace proxima::study
