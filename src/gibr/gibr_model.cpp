#include "proxima/gibr/gibr_model.h"

#include <algorithm>
#include <cmath>

#include "proxima/core/error.h"
#include "proxima/core/image_io.h"
#include "proxima/core/parallel.h"
#include "proxima/core/range_check.h"
#include "proxima/core/rng.h"
#include "proxima/core/timer.h"
#include "proxima/gibr/lens_mapping.h"
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
  if (scene == "colonnade" || scene == "balcony") return {0.02, 1.0};
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

// The camera file's cameras and images (linear RGB, divided by their exposure; taken through
// a lens, kept as taken: map_lens_photograph), each image checked against its camera.
void load_photos(const std::filesystem::path& camera_file, GibrModel& g) {
  const std::vector<CalibratedPhoto> photos = read_camera_file(camera_file);
  if (photos.empty()) fail_input(camera_file.string() + ": the camera file lists no photographs");
  for (const CalibratedPhoto& p : photos) {
    const std::filesystem::path image = camera_file.parent_path() / p.image;
    ImageF linear = read_image_linear(image, 3);
    if (linear.width() != p.camera.width || linear.height() != p.camera.height)
      fail_input(image.string() + ": " + std::to_string(linear.width()) + "×" + std::to_string(linear.height()) +
                 " pixels, but " + camera_file.string() + " gives its camera " + std::to_string(p.camera.width) +
                 "×" + std::to_string(p.camera.height));
    if (p.exposure != 1.0)
      for (float& v : linear.data()) v = float(double(v) / p.exposure);
    g.cameras.push_back(p.camera);
    g.photos.push_back(std::move(linear));
    g.lenses.push_back(Lens{p.k1, p.k2});
  }
  if (std::all_of(g.lenses.begin(), g.lenses.end(), [](const Lens& l) { return l.pinhole(); })) g.lenses.clear();
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

// Phase 1 and what the photographs need: the photographs `given`, the camera file's or
// seeded poses to render from.
GibrModel prepare(const Scene& model_scene, const GibrModelOptions& o, GivenPhotos* given) {
  Stopwatch total;
  check_options(model_scene, o);
  if (given) check_given(*given);
  GibrModel g;
  g.model = extract_polygons(model_scene);
  const GibrSceneDefaults r = resolved(model_scene, g.model, o);
  g.texel = r.texel;
  g.maps.grids = make_texel_grids(g.model, g.texel);  // rejects a texel too small before the photographs
  PhotoSceneOptions pso;
  pso.period = r.period;
  pso.seed = o.seed;
  g.scene = make_photo_scene(model_scene, pso);
  g.far = scene_far_plane(g.scene);
  g.rays = std::make_unique<RayScene>(g.scene);

  Stopwatch w;
  if (given) {
    g.cameras = std::move(given->cameras);
    g.photos = std::move(given->images);
  } else if (!o.camera_file.empty()) {
    load_photos(o.camera_file, g);
  } else {
    PhotoPoseOptions ppo;
    ppo.count = o.photos;
    ppo.width = o.photo_width;
    ppo.height = o.photo_height;
    ppo.seed = o.seed;
    ppo.yaw_deg = o.photo_yaw_deg;
    ppo.backoff = o.photo_backoff;
    g.render_poses = photo_poses(*g.rays, model_scene.camera_paths.front(), ppo, 0.01f, g.far);
    for (size_t i = 0; i < g.render_poses.size(); ++i)
      g.cameras.push_back(miscalibrated(g.render_poses[i], o.calibration_px, derive_seed(o.seed, i, 3)));
  }
  g.stats.photos_ms = w.elapsed_ms();
  // Phase 1: spatial subdivision.
  g.winged_pair = build_winged_pair(g.model, {}, &g.stats.bsp);
  g.stats.total_ms = total.elapsed_ms();
  return g;
}

GibrModel build(const Scene& model_scene, const GibrModelOptions& o, GivenPhotos* given) {
  GibrModel g = prepare(model_scene, o, given);
  std::vector<PhotoMapping> photos;
  if (o.photographs) {
    photos = o.photographs(g);
  } else {
    photos.resize(g.cameras.size());
    parallel_for(photos.size(), 1, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) photos[i] = map_photograph(g, i, o);
    });
  }
  add_photographs(g, std::move(photos), o);
  return g;
}

}  // namespace

GibrModel prepare_gibr_model(const Scene& model_scene, const GibrModelOptions& o) {
  return prepare(model_scene, o, nullptr);
}

namespace {

// map_photograph's phases 2–3 for a photograph taken through a lens (not resampled:
// gibr/lens_mapping.h).
void map_lens_photograph(const GibrModel& g, size_t i, const GibrModelOptions& o, const VisibilityMap& map,
                         const ImageF& photo, const Lens& lens, PhotoMapping& pm) {
  const bool unmix = o.unmix && !o.whole_pixels;
  LensLabels ll = vismap_lens_pixel_polygons(map, g.cameras[i], lens, o.exclude_boundaries, unmix ? o.supersample : 0);
  ImageU32 labels = unmix ? unmix_pixels(ll.labels, photo, ll.unmix, o.unmix_two_pass) : std::move(ll.labels);
  Stopwatch w;
  pm.layers = map_photo_layers(g.model, g.maps.grids, uint32_t(i), g.cameras[i], photo, labels,
                               o.whole_pixels ? nullptr : &map, lens);
  pm.map_ms = w.elapsed_ms();
  if (!o.item_buffer) return;
  w.restart();
  const ImageU32 item_labels = itembuffer_lens_pixel_polygons(*g.rays, g.model, g.cameras[i], lens);
  pm.itembuffer_ms = w.elapsed_ms();
  w.restart();
  pm.item_layers = map_photo_layers(g.model, g.maps.grids, uint32_t(i), g.cameras[i], photo, item_labels, nullptr, lens);
  pm.item_map_ms = w.elapsed_ms();
}

}  // namespace

PhotoMapping map_photograph(const GibrModel& g, size_t i, const GibrModelOptions& o) {
  PhotoMapping pm;
  Stopwatch w;
  if (g.photos.empty())
    pm.photo = render_photo(g.scene, *g.rays, g.render_poses[i], o.supersample, derive_seed(o.seed, i, 1));
  const ImageF& photo = g.photos.empty() ? pm.photo : g.photos[i];
  pm.photo_ms = w.elapsed_ms();
  // Phase 2: the visibility map; kept for phase 3's exact texel-center test in pixels not
  // mapped as a whole (instead of a sub-pixel record: exact, and a third of the labels' memory).
  w.restart();
  VisibilityMap map = trace_visibility_map(g.winged_pair, g.cameras[i]);
  pm.silhouette_edges = double(map.stats.silhouette_edges);
  pm.check = visibility::check_visibility_map(map, g.model, *g.rays, g.cameras[i]);
  const Lens lens = i < g.lenses.size() ? g.lenses[i] : Lens{};
  if (!lens.pinhole()) {
    map_lens_photograph(g, i, o, map, photo, lens, pm);
    pm.vismap_ms = w.elapsed_ms();
    return pm;
  }
  ImageU32 labels = vismap_pixel_polygons(map, o.exclude_boundaries, false);
  if (o.unmix && !o.whole_pixels)
    labels = unmix_silhouette_pixels(map, labels, photo, o.supersample, o.exclude_boundaries, o.unmix_two_pass);
  pm.vismap_ms = w.elapsed_ms();
  // Phase 3: this photograph's radiance-map layers.
  w.restart();
  pm.layers = map_photo_layers(g.model, g.maps.grids, uint32_t(i), g.cameras[i], photo, labels,
                               o.whole_pixels ? nullptr : &map);
  pm.map_ms = w.elapsed_ms();
  if (o.item_buffer) {
    w.restart();
    ImageU32 item_labels = itembuffer_pixel_polygons(g.scene, g.model, g.cameras[i]);
    pm.itembuffer_ms = w.elapsed_ms();
    w.restart();
    pm.item_layers = map_photo_layers(g.model, g.maps.grids, uint32_t(i), g.cameras[i], photo, item_labels, nullptr);
    pm.item_map_ms = w.elapsed_ms();
  }
  return pm;
}

void add_photographs(GibrModel& g, std::vector<PhotoMapping> photos, const GibrModelOptions& o) {
  const size_t n = g.cameras.size();
  if (photos.size() != n) fail_input("gibr: " + std::to_string(photos.size()) + " photograph mappings for " +
                                     std::to_string(n) + " photographs");
  std::vector<PhotoLayers> layers(n), item_layers(n);
  double sum = 0.0, map_ms = 0.0, item_map_ms = 0.0;
  for (size_t i = 0; i < n; ++i) {
    PhotoMapping& pm = photos[i];
    if (g.photos.size() < n) g.photos.push_back(std::move(pm.photo));
    g.stats.photos_ms += pm.photo_ms;
    g.stats.vismap_ms += pm.vismap_ms;
    g.stats.itembuffer_ms += pm.itembuffer_ms;
    g.stats.selfcheck_ms += pm.check.ms;
    sum += pm.silhouette_edges;
    map_ms += pm.map_ms;
    item_map_ms += pm.item_map_ms;
    if (!pm.check.pass) {
      ++g.stats.maps_failed_selfcheck;
      g.stats.selfcheck_failures.push_back("photograph " + std::to_string(i) + ": " + pm.check.reason);
    }
    layers[i] = std::move(pm.layers);
    item_layers[i] = std::move(pm.item_layers);
  }
  g.stats.silhouette_edges_avg = sum / double(n);
  Stopwatch w;
  const std::vector<TexelGrid> grids = g.maps.grids;
  g.maps = merge_photo_layers(grids, g.cameras, std::move(layers));
  g.maps.stats.ms += map_ms;
  if (o.item_buffer) {
    g.item_maps = merge_photo_layers(grids, g.cameras, std::move(item_layers));
    g.item_maps.stats.ms += item_map_ms;
  }
  g.stats.total_ms += w.elapsed_ms() + g.stats.photos_ms + g.stats.vismap_ms + g.stats.itembuffer_ms + map_ms;
}

GibrModel build_gibr_model(const Scene& scene, const GibrModelOptions& options) {
  return build(scene, options, nullptr);
}

GibrModel build_gibr_model(const Scene& scene, const GibrModelOptions& options, GivenPhotos photos) {
  return build(scene, options, &photos);
}

}  // namespace proxima::gibr
