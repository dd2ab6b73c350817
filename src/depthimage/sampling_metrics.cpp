// Sampling-quality metrics (sampling_metrics.h).
// Paper: Xie Naiwen, PhD thesis, ch. 2 §2.3.2 (../shared/papers/004_d1af2812aec5f9c7.txt,
// line 680): view-independent metrics 1–3 (redundant, occluded, useful samples) and the
// view-dependent metric 4 (available samples per output frame).
//
// Symbol ↔ variable:
//   I_i (reference images)      image_sets[s][i]
//   conventional images         conventional[j]
//   intermediate output frames  frame (a conventional DepthImage from viewpoints[k]), K = options.frames
//   "redundant with"            RedundancyTest (sampling.h), or holds() for metric 4
#include "proxima/depthimage/sampling_metrics.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>

#include "proxima/core/parallel.h"

namespace proxima {
namespace {

constexpr size_t kGrain = 4096;  // samples per parallel chunk

// Pixel indices (y·width + x) of the samples of an image, in row order.
std::vector<uint32_t> sample_pixels(const DepthImage& image) {
  std::vector<uint32_t> pixels;
  const auto ids = image.triangle.data();
  for (size_t p = 0; p < ids.size(); ++p)
    if (ids[p] != kNoTriangle) pixels.push_back(uint32_t(p));
  return pixels;
}

// Counts the entries of `items` for which pred(item) holds, in parallel.
size_t count_if_parallel(std::span<const uint32_t> items, const std::function<bool(uint32_t)>& pred) {
  std::atomic<size_t> total{0};
  parallel_for(items.size(), kGrain, [&](size_t begin, size_t end) {
    size_t n = 0;
    for (size_t k = begin; k < end; ++k) n += pred(items[k]);
    total += n;
  });
  return total;
}

double pct(size_t part, size_t whole) { return whole ? 100.0 * double(part) / double(whole) : 0.0; }

// Metric 4's test: does reference image `ref` hold the output-frame sample at pixel
// (x, y) of `from`, depth d, triangle t? (sampling_metrics.h)
class Holds {
 public:
  Holds(Redundancy kind, const Scene& scene, const Camera& from, const DepthImage& ref)
      : kind_(kind), scene_(&scene), from_(&from), ref_(&ref), reproject_(from, ref.camera),
        footprint_(1.0f / focal_length_px(ref.camera)) {}

  bool operator()(int x, int y, float d, uint32_t t) const {
    vec2 r;
    float ref_depth;
    int rx, ry;
    if (!reproject_.map(x, y, d, r, ref_depth) || !pixel_in(ref_->camera, r, rx, ry)) return false;
    const uint32_t held = ref_->triangle.at(rx, ry);
    if (held == t) return true;
    if (kind_ == Redundancy::Pixel || held == kNoTriangle) return false;
    // Visibility: the sample lies on the plane of the held triangle, within 2 footprints.
    const vec3 a = unproject(*from_, vec2(float(x) + 0.5f, float(y) + 0.5f), d);
    const vec3 p0 = scene_->positions[scene_->triangles[held].x];
    return std::abs(glm::dot(triangle_normal(*scene_, held), a - p0)) <= 2.0f * footprint_ * ref_depth;
  }

 private:
  Redundancy kind_;
  const Scene* scene_;
  const Camera* from_;
  const DepthImage* ref_;
  Reprojection reproject_;
  float footprint_;  // pixel size at depth 1 in ref
};

}  // namespace

std::vector<SamplingMetrics> measure_sampling(const Scene& scene, const RayScene& rays, const ViewSet& set,
                                              std::span<const std::vector<DepthImage>> image_sets,
                                              std::span<const DepthImage> conventional,
                                              const MetricsOptions& options, SampleClasses* classes) {
  const Redundancy kind = options.redundancy;
  const int width = set.base.width;
  std::vector<SamplingMetrics> metrics(image_sets.size());
  // occluded[s][i]: pixel indices of the occluded samples; useful flags alongside.
  std::vector<std::vector<std::vector<uint32_t>>> occluded(image_sets.size());
  std::vector<std::vector<std::vector<uint8_t>>> useful(image_sets.size());

  for (size_t s = 0; s < image_sets.size(); ++s) {
    const std::vector<DepthImage>& images = image_sets[s];
    SamplingMetrics& m = metrics[s];
    for (size_t i = 0; i < images.size(); ++i) {
      const DepthImage& image = images[i];
      const std::vector<uint32_t> pixels = sample_pixels(image);
      auto at = [&](uint32_t p, const RedundancyTest& test) {
        const int x = int(p % uint32_t(width)), y = int(p / uint32_t(width));
        return test(x, y, image.depth.at(x, y), image.triangle.at(x, y));
      };
      // Metric 1: redundant with an earlier image of the same set.
      std::vector<RedundancyTest> earlier;
      for (size_t j = 0; j < i; ++j)
        earlier.emplace_back(kind, scene, &rays, image.camera, images[j], options.epsilon);
      m.samples.push_back(pixels.size());
      m.redundant.push_back(count_if_parallel(pixels, [&](uint32_t p) {
        return std::any_of(earlier.begin(), earlier.end(), [&](const RedundancyTest& t) { return at(p, t); });
      }));
      // Metric 2: captured by no conventional image.
      std::vector<RedundancyTest> conv;
      for (const DepthImage& c : conventional)
        conv.emplace_back(kind, scene, &rays, image.camera, c, options.epsilon);
      std::vector<uint8_t> flag(pixels.size());
      parallel_for(pixels.size(), kGrain, [&](size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k)
          flag[k] = std::none_of(conv.begin(), conv.end(), [&](const RedundancyTest& t) { return at(pixels[k], t); });
      });
      std::vector<uint32_t> occ;
      for (size_t k = 0; k < pixels.size(); ++k)
        if (flag[k]) occ.push_back(pixels[k]);
      m.occluded.push_back(occ.size());
      useful[s].emplace_back(occ.size(), uint8_t(0));
      occluded[s].push_back(std::move(occ));
    }
  }

  // Output frames: metric 3 marks occluded samples a frame needs; metric 4 counts the
  // frame's samples the reference images hold.
  const std::vector<vec3> viewpoints = intermediate_viewpoints(set, options.frames, options.seed);
  std::vector<std::vector<double>> available(image_sets.size());
  for (const vec3& viewpoint : viewpoints) {
    const DepthImage frame = render_depth_image(scene, view_camera(set, viewpoint), false);
    const std::vector<uint32_t> frame_pixels = sample_pixels(frame);
    for (size_t s = 0; s < image_sets.size(); ++s) {
      const std::vector<DepthImage>& images = image_sets[s];
      for (size_t i = 0; i < images.size(); ++i) {
        const DepthImage& image = images[i];
        const RedundancyTest needed(kind, scene, &rays, image.camera, frame, options.epsilon);
        const std::vector<uint32_t>& occ = occluded[s][i];
        std::vector<uint8_t>& use = useful[s][i];
        parallel_for(occ.size(), kGrain, [&](size_t begin, size_t end) {
          for (size_t k = begin; k < end; ++k) {
            if (use[k]) continue;
            const int x = int(occ[k] % uint32_t(width)), y = int(occ[k] / uint32_t(width));
            use[k] = needed(x, y, image.depth.at(x, y), image.triangle.at(x, y));
          }
        });
      }
      std::vector<Holds> holds;
      for (const DepthImage& image : images) holds.emplace_back(kind, scene, frame.camera, image);
      const size_t held = count_if_parallel(frame_pixels, [&](uint32_t p) {
        const int x = int(p % uint32_t(width)), y = int(p / uint32_t(width));
        const float d = frame.depth.at(x, y);
        const uint32_t t = frame.triangle.at(x, y);
        return std::any_of(holds.begin(), holds.end(), [&](const Holds& h) { return h(x, y, d, t); });
      });
      available[s].push_back(frame_pixels.empty() ? 100.0 : pct(held, frame_pixels.size()));
    }
  }

  for (size_t s = 0; s < image_sets.size(); ++s) {
    SamplingMetrics& m = metrics[s];
    m.frames = options.frames;
    for (size_t i = 0; i < m.samples.size(); ++i) {
      m.useful.push_back(size_t(std::count(useful[s][i].begin(), useful[s][i].end(), uint8_t(1))));
      m.redundant_pct.push_back(pct(m.redundant[i], m.samples[i]));
      m.occluded_pct.push_back(pct(m.occluded[i], m.samples[i]));
      m.useful_pct.push_back(pct(m.useful[i], m.occluded[i]));
    }
    const std::vector<double>& a = available[s];
    if (a.empty()) {
      m.available_avg_pct = m.available_min_pct = 100.0;
    } else {
      double sum = 0.0;
      for (double v : a) sum += v;  // fixed order: deterministic
      m.available_avg_pct = sum / double(a.size());
      m.available_min_pct = *std::min_element(a.begin(), a.end());
    }
  }

  if (classes) {
    classes->assign(image_sets.size(), {});
    for (size_t s = 0; s < image_sets.size(); ++s) {
      for (size_t i = 0; i < image_sets[s].size(); ++i) {
        ImageU8 c(width, set.base.height, 1, 0);
        for (size_t k = 0; k < occluded[s][i].size(); ++k)
          c.data()[occluded[s][i][k]] = useful[s][i][k] ? 2 : 1;
        (*classes)[s].push_back(std::move(c));
      }
    }
  }
  return metrics;
}

}  // namespace proxima
