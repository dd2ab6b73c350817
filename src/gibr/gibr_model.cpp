#include "proxima/gibr/gibr_model.h"

#include <algorithm>
#include <cmath>

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/gibr/photo_set.h"
#include "proxima/scene/camera_select.h"
#include "proxima/visibility/map_check.h"

namespace proxima::gibr {

using namespace proxima::visibility;

GibrSceneDefaults gibr_scene_defaults(const std::string& scene, double scale) {
  if (scene == "rooms") return {0.02, 1.0};
  if (scene == "floor" || scene == "building") return {0.03, 1.0};
  if (scene == "vcity") return {0.15, 6.0};
  if (scene == "maze") return {0.03, 1.0};
  if (scene == "colonnade") return {0.02, 1.0};
  if (scene == "arena") return {0.05, 2.0};
  return {scale / 500.0, scale / 10.0};
}

namespace {

// The texel and period the options resolve to for this model.
GibrSceneDefaults resolved(const Scene& scene, const ModelPolygons& model, const GibrModelOptions& o) {
  const GibrSceneDefaults def = gibr_scene_defaults(scene.name, model.scale);
  return {o.texel > 0 ? o.texel : def.texel, o.period > 0 ? o.period : def.period};
}

void check_options(const Scene& scene, const GibrModelOptions& o) {
  require_in_range(o.photos, 1, 10000, "--photos");
  require_in_range(o.supersample, 1, 8, "--supersample");
  if (o.texel < 0.0 || !std::isfinite(o.texel)) fail_input("--texel: must be a positive size in meters");
  if (o.period < 0.0 || !std::isfinite(o.period)) fail_input("--period: must be a positive length in meters");
  if (scene.camera_paths.empty()) fail_input("--scene: '" + scene.name + "' has no camera path");
  validate_camera(look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60, o.photo_width, o.photo_height),
                  "--photo-width/--photo-height");
  if (!(o.photo_yaw_deg >= 0.0 && o.photo_yaw_deg <= 180.0)) fail_input("--photo-yaw: must be in 0..180 degrees");
  if (!(o.photo_backoff >= 0.0 && o.photo_backoff <= 1000.0)) fail_input("--photo-backoff: must be in 0..1000 m");
  if (!(o.calibration_px >= 0.0 && o.calibration_px <= 100.0)) fail_input("--calibration-px: must be in 0..100 px");
}

// The camera turned by `px` pixels (at the image center) about an axis in its image plane
// whose direction is seeded: the photograph's pixels then land `px` off where the mapping
// projects them.
Camera miscalibrated(const Camera& c, double px, uint64_t seed) {
  if (px <= 0.0) return c;
  Pcg32 rng(seed, 29);
  const double phi = 2.0 * 3.14159265358979323846 * double(rng.next_float());
  const double angle = std::atan(px / double(focal_length_px(c)));
  Camera out = c;
  out.orientation = glm::normalize(c.orientation * glm::angleAxis(float(angle), vec3(float(std::cos(phi)),
                                                                                     float(std::sin(phi)), 0.0f)));
  return out;
}

// The camera file's cameras and images (linear RGB), each image checked against its camera.
void load_photos(const std::filesystem::path& camera_file, GibrModel& g, std::vector<ImageU8>& valid) {
  const std::vector<CalibratedPhoto> photos = read_camera_file(camera_file);
  if (photos.empty()) fail_input(camera_file.string() + ": the camera file lists no photographs");
  for (const CalibratedPhoto& p : photos) {
    const std::filesystem::path image = camera_file.parent_path() / p.image;
    ImageF linear = read_image_linear(image, 3);
    if (linear.width() != p.camera.width || linear.height() != p.camera.height)
      fail_input(image.string() + ": " + std::to_string(linear.width()) + "×" + std::to_string(linear.height()) +
                 " pixels, but " + camera_file.string() + " gives its camera " + std::to_string(p.camera.width) +
                 "×" + std::to_string(p.camera.height));
    ImageU8 ok;
    if (p.k1 != 0.0 || p.k2 != 0.0) linear = undistort_photo(linear, p.camera, p.k1, p.k2, &ok);
    if (p.exposure != 1.0)
      for (float& v : linear.data()) v = float(double(v) / p.exposure);
    g.cameras.push_back(p.camera);
    g.photos.push_back(std::move(linear));
    valid.push_back(std::move(ok));
  }
}

// Pixels within √2/2 + 1 px of a silhouette edge (the touched band widened by the bilinear
// kernel of the undistortion) are mapped onto nothing.
void drop_resampled_band(ImageU32& labels, const VisibilityMap& map) {
  const ImageU8 band = silhouette_pixel_mask(map, std::sqrt(0.5) + 1.0);
  for (int y = 0; y < labels.height(); ++y)
    for (int x = 0; x < labels.width(); ++x)
      if (band.at(x, y)) labels.at(x, y) = kNone;
}

// Pixels without an image (0 in `valid`, when not empty) are mapped onto nothing and unmixed
// for nothing.
void drop_invalid(ImageU32& labels, const ImageU8& valid) {
  if (valid.width() == 0) return;
  const int uc = unmix_channel(labels);
  for (int y = 0; y < labels.height(); ++y)
    for (int x = 0; x < labels.width(); ++x) {
      if (valid.at(x, y)) continue;
      labels.at(x, y) = kNone;
      if (uc >= 0) labels.at(x, y, uc) = kNone;
    }
}

void check_given(const GivenPhotos& p) {
  if (p.images.empty() || p.images.size() > 10000) fail_input("photos: expected 1..10000 photographs");
  if (p.cameras.size() != p.images.size())
    fail_input("photos: " + std::to_string(p.images.size()) + " photographs but " + std::to_string(p.cameras.size()) +
               " cameras");
  for (size_t i = 0; i < p.images.size(); ++i) {
    validate_camera(p.cameras[i], "cameras");
    const ImageF& image = p.images[i];
    if (image.channels() != 3 || image.width() != p.cameras[i].width || image.height() != p.cameras[i].height)
      fail_input("photos: photograph " + std::to_string(i) + " is " + std::to_string(image.width()) + "×" +
                 std::to_string(image.height()) + "×" + std::to_string(image.channels()) + ", its camera " +
                 std::to_string(p.cameras[i].width) + "×" + std::to_string(p.cameras[i].height) + "×3");
  }
}

// Phases 1–3; the photographs are `given`, the camera file's or rendered from seeded poses.
GibrModel build(const Scene& model_scene, const GibrModelOptions& o, GivenPhotos* given) {
  Stopwatch total;
  check_options(model_scene, o);
  if (given) check_given(*given);
  GibrModel g;
  g.model = extract_polygons(model_scene);
  const GibrSceneDefaults r = resolved(model_scene, g.model, o);
  g.texel = r.texel;
  (void)make_texel_grids(g.model, g.texel);  // rejects a texel too small before the photographs
  PhotoSceneOptions pso;
  pso.period = r.period;
  pso.seed = o.seed;
  g.scene = make_photo_scene(model_scene, pso);
  g.far = scene_far_plane(g.scene);
  g.rays = std::make_unique<RayScene>(g.scene);

  Stopwatch w;
  std::vector<ImageU8> valid;  // per camera-file photograph: empty, or 0 where undistortion had no source
  if (given) {
    g.cameras = std::move(given->cameras);
    g.photos = std::move(given->images);
  } else if (!o.camera_file.empty()) {
    load_photos(o.camera_file, g, valid);
  } else {
    PhotoPoseOptions ppo;
    ppo.count = o.photos;
    ppo.width = o.photo_width;
    ppo.height = o.photo_height;
    ppo.seed = o.seed;
    ppo.yaw_deg = o.photo_yaw_deg;
    ppo.backoff = o.photo_backoff;
    g.cameras = photo_poses(*g.rays, model_scene.camera_paths.front(), ppo, 0.01f, g.far);
    g.photos.resize(g.cameras.size());
    for (size_t i = 0; i < g.cameras.size(); ++i) {
      g.photos[i] = render_photo(g.scene, *g.rays, g.cameras[i], o.supersample, derive_seed(o.seed, i, 1));
      g.cameras[i] = miscalibrated(g.cameras[i], o.calibration_px, derive_seed(o.seed, i, 3));
    }
  }
  g.stats.photos_ms = w.elapsed_ms();

  // Phase 1: spatial subdivision.
  g.winged_pair = build_winged_pair(g.model, {}, &g.stats.bsp);
  // Phase 2: a visibility map per photograph (and the baseline's item buffers).
  w.restart();
  const size_t n = g.cameras.size();
  std::vector<ImageU32> labels(n);
  std::vector<double> silhouettes(n);
  std::vector<visibility::MapCheck> checks(n);
  // Kept until phase 3 for the exact texel-center test in pixels not mapped as a whole
  // (instead of a sub-pixel record: exact, and a third of the labels' memory).
  std::vector<VisibilityMap> vis_maps(o.whole_pixels ? 0 : n);
  parallel_for(n, 1, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      VisibilityMap map = trace_visibility_map(g.winged_pair, g.cameras[i]);
      silhouettes[i] = double(map.stats.silhouette_edges);
      checks[i] = visibility::check_visibility_map(map, g.model, *g.rays, g.cameras[i]);
      labels[i] = vismap_pixel_polygons(map, o.exclude_boundaries, false);
      // An undistorted photograph is a bilinear resample: its pixels within 1 px of a touched
      // one mix the silhouette's sides too, and no pixel averages the map's sample points.
      const bool resampled = i < valid.size() && valid[i].width() > 0;
      if (resampled) drop_resampled_band(labels[i], map);
      if (o.unmix && !o.whole_pixels && !resampled)
        labels[i] = unmix_silhouette_pixels(map, labels[i], g.photos[i], o.supersample, o.exclude_boundaries,
                                            o.unmix_two_pass);
      if (i < valid.size()) drop_invalid(labels[i], valid[i]);
      if (!o.whole_pixels) vis_maps[i] = std::move(map);
    }
  });
  g.stats.vismap_ms = w.elapsed_ms();
  double sum = 0.0;
  for (double s : silhouettes) sum += s;
  g.stats.silhouette_edges_avg = sum / double(n);
  for (size_t i = 0; i < n; ++i) {
    g.stats.selfcheck_ms += checks[i].ms;
    if (checks[i].pass) continue;
    ++g.stats.maps_failed_selfcheck;
    g.stats.selfcheck_failures.push_back("photograph " + std::to_string(i) + ": " + checks[i].reason);
  }
  std::vector<ImageU32> item_labels;
  if (o.item_buffer) {
    w.restart();
    item_labels.resize(n);
    for (size_t i = 0; i < n; ++i) {
      item_labels[i] = itembuffer_pixel_polygons(g.scene, g.model, g.cameras[i]);
      if (i < valid.size()) drop_invalid(item_labels[i], valid[i]);
    }
    g.stats.itembuffer_ms = w.elapsed_ms();
  }
  // Phase 3: radiance maps.
  g.maps = build_radiance_maps(g.model, g.texel, g.cameras, g.photos, labels, vis_maps);
  vis_maps = {};
  if (o.item_buffer) g.item_maps = build_radiance_maps(g.model, g.texel, g.cameras, g.photos, item_labels);
  g.stats.total_ms = total.elapsed_ms();
  return g;
}

}  // namespace

GibrModel build_gibr_model(const Scene& scene, const GibrModelOptions& options) {
  return build(scene, options, nullptr);
}

GibrModel build_gibr_model(const Scene& scene, const GibrModelOptions& options, GivenPhotos photos) {
  return build(scene, options, &photos);
}

}  // namespace proxima::gibr
