// Shared machinery of the demo sections (demo_sections.h): study runs, images, crops.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "demo_sections.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/eval/image_error.h"

namespace proxima::study::demo {

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "–";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

namespace {

std::string shell_quote(const std::string& a) {
  if (!a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=,:") ==
                        std::string::npos)
    return a;
  std::string q = "'";
  for (char ch : a) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

}  // namespace

StudyRun run_study(Context& c, const std::string& dir, std::vector<std::string> args,
                   const std::function<Results(const study::StudyOutput&)>& study) {
  const DemoStudyRun spec{dir, args};
  const std::filesystem::path out = c.out / dir;
  if (!c.plan) std::filesystem::create_directories(out);
  args.insert(args.begin(), "proxima");
  args.push_back("--out");
  args.push_back((std::filesystem::path(c.out_arg) / dir).string());
  if (c.threads > 0) {
    args.push_back("--threads");
    args.push_back(std::to_string(c.threads));
  }
  StudyRun run;
  run.dir = dir;
  for (const std::string& a : args) run.command += (run.command.empty() ? "" : " ") + shell_quote(a);
  c.progress->step(dir);
  if (c.plan) {
    c.plan->push_back(spec);
    return run;
  }
  run.results = c.source ? (*c.source)(spec) : study(study::StudyOutput{out});
  run.results.command = args;
  run.results.threads = active_threads();
  write_results_json(out / "results.json", run.results);
  return run;
}

double metric(const Results& r, const std::string& name) {
  auto it = r.metrics.find(name);
  return it == r.metrics.end() ? std::nan("") : it->second;
}

void add_image(Context& c, Section& s, const std::string& role, const std::string& file) {
  c.results->images[role] = file;
  s.images.push_back(role);
}

ImageF read_study_image(const Context& c, const std::string& file) {
  if (c.plan) return ImageF(1, 1, 3, 0.0f);
  return read_image_linear(c.out / file, 3);
}

Window worst_window(const ImageF& error, int size) {
  Window best{0, 0, std::min({size, error.width(), error.height()})};
  const int n = best.size, stride = std::max(1, n / 8);
  double best_sum = -1.0;
  for (int y = 0; y + n <= error.height(); y += stride)
    for (int x = 0; x + n <= error.width(); x += stride) {
      double sum = 0.0;
      for (int j = y; j < y + n; ++j)
        for (int i = x; i < x + n; ++i) sum += error.at(i, j);
      if (sum > best_sum) best_sum = sum, best.x = x, best.y = y;
    }
  return best;
}

ImageF crop_zoom(const ImageF& image, const Window& w, int zoom) {
  ImageF out(w.size * zoom, w.size * zoom, image.channels());
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x)
      for (int k = 0; k < image.channels(); ++k) out.at(x, y, k) = image.at(w.x + x / zoom, w.y + y / zoom, k);
  return out;
}

ImageF side_by_side(const std::vector<ImageF>& images, int shrink) {
  int width = 0, height = 0;
  for (const ImageF& im : images) {
    width += im.width() / shrink + 4;
    height = std::max(height, im.height() / shrink);
  }
  ImageF out(std::max(1, width - 4), std::max(1, height), 3, 1.0f);
  int x0 = 0;
  for (const ImageF& im : images) {
    const int w = im.width() / shrink, h = im.height() / shrink;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int k = 0; k < 3; ++k) {
          float sum = 0.0f;
          for (int j = 0; j < shrink; ++j)
            for (int i = 0; i < shrink; ++i) sum += im.at(x * shrink + i, y * shrink + j, std::min(k, im.channels() - 1));
          out.at(x0 + x, y, k) = sum / float(shrink * shrink);
        }
    x0 += w + 4;
  }
  return out;
}

void write_image(Context& c, Section& s, const std::string& role, const std::string& file, const ImageF& image) {
  add_image(c, s, role, file);
  if (c.plan) return;
  std::filesystem::create_directories((c.out / file).parent_path());
  write_png_linear(c.out / file, image);
}

void add_heatmap_legend(Context& c, Section& s, float max_error) {
  const std::string file = "heatmap_legend_0_" + fixed(max_error, 0) + ".png";
  if (!c.plan && !std::filesystem::exists(c.out / file)) write_png_linear(c.out / file, heatmap_legend(256, 20));
  add_image(c, s, "heat-map legend: error 0 (left, black) to ≥ " + fixed(max_error, 0) + " (right, yellow), 0–255 display scale", file);
}

}  // namespace proxima::study::demo
