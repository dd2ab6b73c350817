// The four sampling-quality metrics of thesis ch. 2 §2.3.2, for either redundancy
// definition. Percentages are of samples (pixels holding a sample), not of all pixels.
//  1. redundant_pct[i]: samples of I_i redundant with some I_j, j < i.
//  2. occluded_pct[i]: samples of I_i captured by none of the n conventional images
//     (not redundant with any of them). All n, not only j < i: NRR image i is by
//     construction non-redundant with NRR images j < i (image 0 is conventional), so
//     "j < i" would make every NRR sample of image 1 occluded; the thesis' 62 %/76 %
//     for the nest and its definition for depth peeling both count against all n.
//  3. useful_pct[i]: occluded samples of I_i that at least one of K output frames needs,
//     i.e. that are redundant with the conventional image of an intermediate viewpoint
//     (as % of the occluded samples).
//  4. available_avg_pct / available_min_pct: per output frame, the % of its samples that
//     are available in the reference set, i.e. that some I_i holds:
//     - pixel: the sample reprojected into I_i lands on the same triangle (Algorithm 3
//       turned around);
//     - visibility: the sample reprojected into I_i lands on a pixel whose triangle's
//       plane passes within 2 pixel footprints (of I_i, at the sample's depth) of the
//       sample point — "I_i sees this surface point", tested against what I_i holds
//       (Algorithm 2's ray from V_i would ignore what NRR and peeling discarded).
//     Mean and minimum over the K frames.
// Output frames: conventional images (same size, culling) from K viewpoints drawn
// uniformly in the view set's region (intermediate_viewpoints, seeded).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "proxima/depthimage/depth_image.h"
#include "proxima/depthimage/sampling.h"
#include "proxima/depthimage/view_set.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

struct SamplingMetrics {
  std::vector<size_t> samples;    // per image
  std::vector<size_t> redundant;  // per image, metric 1
  std::vector<size_t> occluded;   // per image, metric 2
  std::vector<size_t> useful;     // per image, metric 3 (subset of occluded)
  std::vector<double> redundant_pct, occluded_pct, useful_pct;
  double available_avg_pct = 0.0;  // metric 4 (100 when there are no frames)
  double available_min_pct = 0.0;
  int frames = 0;
};

struct MetricsOptions {
  Redundancy redundancy = Redundancy::Pixel;
  int frames = 1000;  // K output frames
  uint64_t seed = 1;  // of the intermediate viewpoints
  float epsilon = kVisibilityEpsilon;
};

// Per-pixel classes for the thesis' Table 3 visualisation, classes[set][image]: 0 = no
// sample or not occluded, 1 = occluded, 2 = occluded and useful.
using SampleClasses = std::vector<std::vector<ImageU8>>;

// Metrics of several image sets of the same view set at once (one per sampling method),
// sharing the K output frames. `conventional`: the conventional images of set's corners
// (metric 2). `rays`: the BVH of `scene`. Every image and the output frames have
// set.base's resolution. `classes` (optional) receives the Table 3 classes.
// Deterministic for any thread count (integer counts only).
std::vector<SamplingMetrics> measure_sampling(const Scene& scene, const RayScene& rays, const ViewSet& set,
                                              std::span<const std::vector<DepthImage>> image_sets,
                                              std::span<const DepthImage> conventional,
                                              const MetricsOptions& options, SampleClasses* classes = nullptr);

}  // namespace proxima
