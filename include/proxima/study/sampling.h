// The depth-image sampling study (thesis ch. 2; docs/depthimage.md): a scene sampled with n
// depth images by one or more methods (conventional, depth peeling, NRR with pixel or
// visibility redundancy), each method timed side by side, and the four sampling metrics
// measured against K intermediate output frames shared by every method.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "proxima/core/progress.h"
#include "proxima/depthimage/sampling.h"
#include "proxima/depthimage/view_set.h"
#include "proxima/eval/results.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/scene.h"
#include "proxima/study/study.h"

namespace proxima::study {

enum class SamplingMethod {
  Conventional,   // one conventional depth image per corner of the view set
  Peeling,        // n depth-peeling layers from the view set's centroid
  NrrPixel,       // non-redundant rendering from the corners, pixel redundancy (Algorithm 3)
  NrrVisibility,  // non-redundant rendering from the corners, visibility redundancy (Algorithm 2)
};
// "conventional" | "peeling" | "nrr-pixel" | "nrr-visibility" (the --method names).
const char* sampling_method_name(SamplingMethod m);
// Throws InputError naming `flag` and the valid names for anything else.
SamplingMethod parse_sampling_method(const std::string& name, const char* flag);

// The options of `proxima sample`, one field per flag, with the flag's default.
struct SamplingOptions {
  CameraChoice camera;  // --camera, --path, --frame: the view set's centre and direction
  int width = 1024;     // --width, pixels, of every depth image and output frame
  int height = 1024;    // --height, pixels (the command defaults it to --width)
  uint64_t seed = 1;    // --seed, of the K intermediate viewpoints
  std::vector<SamplingMethod> methods{SamplingMethod::NrrPixel};  // --method; several share the frames
  ViewShape views = ViewShape::Triangle;  // --views: segment (2 views), triangle (3), rectangle (4)
  // --redundancy: the definition every metric uses; none = visibility when nrr-visibility
  // is the only NRR method, else pixel.
  std::optional<Redundancy> redundancy;
  int frames = 1000;    // --frames, K intermediate output frames (0..100000)
  float radius = 0.0f;  // --radius, m, of the views from the centre; 0 = 8 % of the focus distance
  int reps = 3;         // --reps, timed repetitions of each method (the median is reported), 1..100
};

// Throws InputError naming the flag (--width/--height, --method, --frames, --radius, --reps)
// for a value out of range.
void validate(const SamplingOptions& options);
// The options on `scene`: validate(options), and the camera choice resolves (errors name
// --camera, --path or --frame).
void validate(const SamplingOptions& options, const Scene& scene);

// The redundancy definition the metrics use: options.redundancy, or its default.
Redundancy metric_redundancy(const SamplingOptions& options);

// The view set of the options (centred on their camera, radius 8 % of the distance to the
// scene's centre unless given) and its cameras: the corners' (conventional, NRR) and the
// centroid's (peeling).
struct SamplingViews {
  ViewSet set;
  std::vector<Camera> corners;
  Camera centroid;
};
SamplingViews sampling_views(const Scene& scene, const SamplingOptions& options);

// Runs the study. Metrics per method and image i: redundant_pct_<i>, occluded_pct_<i>,
// useful_pct_<i>, then available_avg_pct, available_min_pct, time_ms (median ms to sample
// all n images, shaded); with several methods each name carries the method's prefix
// (conventional_, peeling_, nrr_pixel_, nrr_visibility_). Also metrics_ms, triangles,
// frames. Tables: the thesis' Table 2 / 5 shape, available samples (Table 4 / 6 shape),
// per image, timings. Images (role = file stem) per method and image i:
// <method>_<i>_color.png, _depth.exr, _id.exr (triangle id as float, −1 empty),
// _occluded.png (thesis Table 3 colours). The sampled images and metrics are deterministic
// for any thread count; `progress` is not used (the study is one step of a caller's bar).
// Throws InputError for invalid options.
Results run_sampling(const Scene& scene, const SamplingOptions& options, const StudyOutput& out,
                     Progress* progress = nullptr);

}  // namespace proxima::study
