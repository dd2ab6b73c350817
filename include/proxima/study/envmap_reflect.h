// The environment-map reflection experiment (`proxima reflect`, docs/envmap.md): a
// reflector's mirror reflection through environment maps with distance — plain, rectified,
// average-distance, layered (Wang et al. 2012) — beside the Embree reference on the same
// camera and pixels (one bounce). Per method: the error over the reflector and over its
// environment-only pixels, how often the lookup found the reference's object, the edge-rule
// share, and the frame time (median of round-robin repetitions) with and without the map
// build.
#pragma once

#include <cstdint>
#include <string>

#include "proxima/core/progress.h"
#include "proxima/eval/results.h"
#include "proxima/reflect/envmap_groups.h"
#include "proxima/reflect/envmap_reflection.h"
#include "proxima/scene/camera_select.h"
#include "proxima/scene/scene.h"
#include "proxima/study/study.h"

namespace proxima::study {

// The method names of --method this study runs, in the order of its results table:
// the four env-map methods (reflect/envmap_reflection.h), the box-projected probe (the
// engines' baseline, reflect/box_probe.h), then the reference.
inline constexpr const char* kEnvmapReflectMethods[] = {"envmap",   "rectified", "average",
                                                        "layered",  "boxprobe",  "reference"};

// One field per flag of `proxima reflect` (env-map methods), with the command's defaults.
struct EnvmapReflectOptions {
  std::string method = "rectified";  // --method: one of kEnvmapReflectMethods ("reference" = the reference alone)
  bool compare = false;              // --compare: every method of kEnvmapReflectMethods instead of `method`
  CameraChoice camera;               // --camera, or --path with --frame (animated objects posed at that frame)
  int width = 1024, height = 768;    // --width, --height: image size in pixels
  uint64_t seed = 1;                 // --seed: area-light, lobe and map texel streams
  float d_e = 0.01f;                 // --d-e: rectification tolerance d_e, meters
  float distance = 0.0f;             // --distance: search length D, meters; 0 = the scene's bounding-box diagonal
  int cube_size = 512;               // --cube-size: cube-map face side, texels
  float angle_step_deg = 2.0f;       // --angle-step: sampling step s of the average distance, degrees
  std::string edge = "black";        // --edge: "black" or "fallback" (plain lookup) where the search ends beside the map
  int light_samples = 4;             // --light-samples: n of the n×n samples per area light
  int glossy_rays = 16;              // --glossy-rays: lobe rays (lookups) per glossy pixel
  int reps = 3;                      // --reps: timed frames per method, round-robin over the methods
  int layers = 3;                    // --layers: layered: depth layers peeled from the map's center
  int march_steps = 64;              // --march-steps: layered: ray-march samples per lookup at most
  int max_maps = 4;                  // --max-maps: env maps (groups of reflectors) at most; 1 = one shared map
  float group_parallax = EnvmapGroupOptions{}.max_parallax;  // --group-parallax: reflectors share a map while its parallax is ≤ this
};

// Throws InputError naming the flag for an option out of range.
void validate(const EnvmapReflectOptions& options);
// The same, and what depends on the scene: the camera choice (--camera, --path, --frame)
// and a reflective object to study (--scene). Callers check before writing anything.
void validate(const EnvmapReflectOptions& options, const Scene& scene);

// The lookup and sampling settings these options give (method, rectification, light and lobe
// samples, seed), without the maps (EnvmapInputs::map, layers, average_distance are left
// unset); "reference" gives Rectified. For callers that build the maps themselves.
EnvmapInputs envmap_inputs(const Scene& scene, const EnvmapReflectOptions& options);

// Renders the reference and the chosen methods on the camera of `options` and compares them.
// boxprobe reads the same distance cube map as plain / rectified / average, its proxy box
// probe_proxy_box(scene) (metrics probe_box_min_x … probe_box_max_z).
// Metrics (per method m): m_mae, m_env_mae, m_ms, m_with_build_ms, m_object_match_pct, and for
// the env-map methods m_edge_pct, m_samples_per_lookup; shared: reflector_pixels,
// self_reflection_pct, D_m, d_e_m, N, envmap_build_ms, average_distance_ms,
// average_distance_m, and for layered layered_build_ms, layers, viewer_radius_m,
// layer<k>_shaded_texels, layer<k>_hidden_texels, layered_fallback_pct. One table (a row per
// method). Images per method m run: m.png, and for the env-map methods (the reference outside
// the reflector) error_m.png, the error heat map on the reflector (0 … kErrorHeatmapMax).
// Throws InputError as validate(options, scene) does, before anything is written.
// Deterministic for any thread count (timings aside).
Results run_envmap_reflect(const Scene& scene, const EnvmapReflectOptions& options, const StudyOutput& out,
                           Progress* progress = nullptr);

}  // namespace proxima::study
