// The viewer's technique registry: every rendering technique the viewer can
// switch to, each a thin wrapper around the library code its `proxima` command runs
// (reference ray tracing, env maps, cluster and temporal reflections, soft shadows from
// reconstructed depth images, GIBR novel views), with a frame time per step. Platform
// independent.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/gibr/gibr_model.h"
#include "proxima/reflect/reflection_frame.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima {

// A scene with its BVH, shared by every technique.
struct ViewerScene {
  Scene scene;
  RayScene rays;
  explicit ViewerScene(Scene s) : scene(std::move(s)), rays(scene) {}
};

struct StepTime {
  std::string name;
  double ms = 0.0;
};

struct TechniqueFrame {
  ImageF color;                 // linear RGB, camera.width × camera.height
  std::vector<StepTime> steps;  // in order; one-off builds are named "... (once)"
  std::string note;             // one line for the overlay (e.g. "building the GIBR model...")
  // Not a frame of the view yet (a one-off build is announced, or failed): shown, but never
  // kept as the refined frame, so the next frame renders again.
  bool pending = false;
};

// Quality knobs of the live techniques (the viewer trades quality for frame rate) and of
// the references the error is measured against: the techniques' own options, whose seeds
// `seed` replaces.
struct TechniqueSettings {
  // Live reference ray tracing: mirror reflections (1 glossy ray, 1 bounce), hard shadows
  // (one area-light sample).
  ReferenceOptions live{.area_light_samples = 1, .glossy_rays = 1, .max_bounces = 1};
  // The reference of the error overlay (render_reference's defaults); its rows are the
  // band asked for.
  ReferenceOptions reference;
  // Env maps, cluster, temporal: the G-buffer at one sample per pixel, its glossy lobe rays
  // and area-light samples (also the cube map's).
  ReflectionOptions reflection{.supersample = 1, .glossy_rays = 4, .area_light_samples = 1};
  int cube_size = 256;
  // Soft shadows (`proxima shadows`): light diagonal / scene diagonal, n×n samples.
  float shadow_light_size = 0.25f;
  int shadow_light_samples = 2;
  int occluder_resolution = 512;
  int shadow_map_resolution = 512;
  // GIBR novel views: the model built once (`proxima demo`'s quick settings: photographs
  // along the scene's first path), k photographs blended per pixel.
  gibr::GibrModelOptions gibr_model{
      .photos = 16, .photo_width = 160, .photo_height = 120, .supersample = 2, .camera_file = {}};
  int gibr_k = 3;
  uint64_t seed = 1;
};

struct Technique {
  std::string name;         // as the commands spell it: "reference", "envmap", ...
  std::string label;        // one line for the panel
  char key = 0;             // '1'..'9' switches to it
  std::string unavailable;  // non-empty: why it cannot run here (the panel shows it)
  // One frame from `camera` (any size).
  std::function<TechniqueFrame(const Camera&)> render;
  // Its ground truth over rows [row_begin, row_end) (other rows 0): render_reference at
  // the reference quality, or exact shadow rays for the shadow technique, which computes
  // every row at once (whole_reference).
  std::function<ImageF(const Camera&, int row_begin, int row_end)> reference;
  bool whole_reference = false;
  // Its parameter key ('-' halves, '=' doubles a knob; empty = none): returns e.g.
  // "cube map faces 512". The next frame uses the new value.
  std::function<std::string(int step)> adjust;
  // Drops state carried between frames (temporal reuse); called on a switch or resize.
  std::function<void()> reset = [] {};
};

// The registry in key order. Techniques needing a reflective object are unavailable
// (with the reason) in scenes without one, GIBR in scenes that are not visibility models.
// `scene` must outlive the techniques.
std::vector<Technique> make_techniques(std::shared_ptr<ViewerScene> scene, const TechniqueSettings& settings);

}  // namespace proxima
