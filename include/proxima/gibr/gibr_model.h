// Phases 1–3 of hybrid geometry- and image-based rendering in one call (Funkhouser,
// section 2): from a polygonal scene with a walkthrough path to a model ready for novel
// views — synthetic calibrated photographs of its textured, lit copy, the spatial
// subdivision (BSP → winged pair), a visibility map per photograph, and the radiance maps
// (optionally also the item-buffer baseline's). `proxima gibr` and the viewer's GIBR
// technique both build through it. docs/gibr.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/gibr/lens.h"
#include "proxima/gibr/radiance_map.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/bsp_build.h"
#include "proxima/visibility/map_check.h"
#include "proxima/visibility/polygons.h"
#include "proxima/visibility/winged_pair.h"

namespace proxima::gibr {

// Texel size and texture period per built-in visibility model: texels about the size of a
// photograph pixel's footprint at typical distances along the walk (docs/gibr.md); other
// scenes: scale / 500 and scale / 10 (scale = the polygons' bounding-box diagonal).
struct GibrSceneDefaults {
  double texel = 0.02, period = 1.0;
};
GibrSceneDefaults gibr_scene_defaults(const std::string& scene_name, double scale);

struct GibrModel;
struct PhotoMapping;

struct GibrModelOptions {
  int photos = 100;                     // along the scene's first camera path, ≥ 1
  int photo_width = 320, photo_height = 240;
  double texel = 0.0;                   // meters; 0 = gibr_scene_defaults
  double period = 0.0;                  // texture repeat, meters; 0 = gibr_scene_defaults
  int supersample = 2;                  // k×k samples per photograph pixel
  bool exclude_boundaries = false;      // vismap_pixel_polygons' option
  bool whole_pixels = false;            // vismap_pixel_polygons without the sub-pixel record
  bool unmix = true;                    // unmix_silhouette_pixels (needs the sub-pixel record)
  bool unmix_two_pass = false;          // unmix_silhouette_pixels' two_pass (thin occluders)
  bool item_buffer = false;             // also map through item buffers (the baseline)
  // Regimes of the sweep (docs/gibr.md): the photographs' poses (photo_poses' yaw range and
  // backoff) and a calibration error — the cameras the mapping uses are the poses the
  // photographs were taken from turned by `calibration_px` pixels (at the image center) in a
  // seeded direction per photograph, as a real calibration is off by a pixel or two.
  double photo_yaw_deg = 30.0;          // ±yaw of the photographs' view directions, 0..180
  double photo_backoff = 0.0;           // meters the photographs step back, 0..1000
  double calibration_px = 0.0;          // 0..100
  uint64_t seed = 1;
  // Supplies every photograph's mapping, in photograph order (map_photograph of each, e.g.
  // computed by other processes: proxima sweep); empty = mapped here, in parallel.
  std::function<std::vector<PhotoMapping>(const GibrModel&)> photographs = {};
  // Non-empty: the photographs are the images of this camera file (photo_set.h; e.g. real
  // photographs of the model), not rendered; `photos`, `photo_width` / `photo_height` are
  // then unused and `supersample` only tells the unmixing how finely the images average.
  // Each image is divided by its exposure as it is loaded and kept as the lens took it: both
  // mappings label its pixels where they are and sample it once, through the camera's k1, k2
  // (gibr/lens_mapping.h).
  std::filesystem::path camera_file;
};

struct GibrModelStats {
  double photos_ms = 0.0;       // reference renders of the photographs
  visibility::BspStats bsp;     // phase 1 (build_ms)
  double vismap_ms = 0.0;       // phase 2, all photographs (includes selfcheck_ms)
  double itembuffer_ms = 0.0;   // phase 2', all photographs (item_buffer only)
  double silhouette_edges_avg = 0.0;  // per visibility map
  // Self-check of every photograph's visibility map (visibility/map_check.h).
  size_t maps_failed_selfcheck = 0;
  std::vector<std::string> selfcheck_failures;  // one line per failed map: photograph index and reason
  double selfcheck_ms = 0.0;                     // all photographs
  double total_ms = 0.0;
};

struct GibrModel {
  Scene scene;                          // the textured, lit photo scene (same geometry)
  std::unique_ptr<RayScene> rays;       // of `scene`: photographs and ground truth
  visibility::ModelPolygons model;      // extract_polygons of the input scene
  visibility::WingedPair winged_pair;   // phase 1
  double texel = 0.0, far = 0.0;        // texel size used; far plane of every camera
  std::vector<Camera> cameras;          // per photograph, as the mapping uses it (calibrated)
  std::vector<ImageF> photos;           // linear RGB (camera-file photographs divided by their exposure)
  std::vector<Camera> render_poses;     // rendered photographs: the poses they are taken from
  std::vector<Lens> lenses;             // camera-file photographs' lenses (images kept as taken); empty: all pinhole
  RadianceMaps maps;                    // visibility-map mapping (phase 3)
  RadianceMaps item_maps;               // item-buffer mapping; empty unless options.item_buffer
  GibrModelStats stats;
};

// The per-photograph phases of one photograph: its image (rendered, or the camera file's),
// visibility map (phase 2: silhouettes, self-check, pixel labels) and its radiance-map layers
// (phase 3) through the visibility map and, with item_buffer, through an item buffer.
struct PhotoMapping {
  ImageF photo;
  double silhouette_edges = 0.0;
  visibility::MapCheck check;
  PhotoLayers layers, item_layers;
  double photo_ms = 0.0, vismap_ms = 0.0, itembuffer_ms = 0.0, map_ms = 0.0, item_map_ms = 0.0;
};

// Everything but the per-photograph phases: the photo scene, cameras, phase 1 and the texel
// grids (maps.grids); photos only from a camera file.
GibrModel prepare_gibr_model(const Scene& scene, const GibrModelOptions& options);

// Photograph `index` of a prepared model (the same options). Deterministic.
PhotoMapping map_photograph(const GibrModel& g, size_t index, const GibrModelOptions& options);

// Completes a prepared model from its photographs' mappings (all, in photograph order): the
// radiance maps merged in that order, the statistics (the phases' times summed over the
// photographs).
void add_photographs(GibrModel& g, std::vector<PhotoMapping> photos, const GibrModelOptions& options);

// Builds the model (prepare_gibr_model, map_photograph of every photograph — or
// options.photographs — and add_photographs). A camera file that is missing or malformed, or whose images are
// unreadable or not the size its cameras say, throws InputError naming the file. Invalid
// options (photos outside 1..10000, supersample outside 1..8, a negative texel or period, a
// bad photograph size, a texel too small for the model) or a scene without a camera path
// throw InputError naming the `proxima gibr` flag, before any work. Deterministic for a seed, at any thread count.
GibrModel build_gibr_model(const Scene& scene, const GibrModelOptions& options = {});

// Calibrated photographs held in memory: images[i] (linear RGB, 3 channels, the size of
// cameras[i]) was taken by cameras[i].
struct GivenPhotos {
  std::vector<Camera> cameras;
  std::vector<ImageF> images;
};

// The same from `photos` instead of rendered or camera-file photographs (options.photos,
// photo_width, photo_height and camera_file unused). InputError naming "photos" for none,
// more than 10000, a count different from the cameras', or an image that is not 3 channels
// of its camera's size; "cameras" for an invalid camera.
GibrModel build_gibr_model(const Scene& scene, const GibrModelOptions& options, GivenPhotos photos);

}  // namespace proxima::gibr
