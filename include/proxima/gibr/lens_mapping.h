// Mapping a photograph taken through a lens with radial distortion (gibr/lens.h) without
// resampling it: its pixels are labeled where they are, in the lens image, by querying the
// visibility map (which lives in the pinhole image) at each pixel's undistorted position, and
// the radiance maps sample the photograph once, at each texel's projection through the
// pinhole camera and the lens (radiance_map.h map_photo_layers with the lens). Resampling
// the photograph to a pinhole image first would blur it and mix the sides of its
// silhouettes over a band a pixel wider (docs/gibr.md).
#pragma once

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/gibr/lens.h"
#include "proxima/gibr/radiance_map.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/visibility/polygons.h"
#include "proxima/visibility/visibility_map.h"

namespace proxima::gibr {

struct LensLabels {
  ImageU32 labels;     // 1 channel, as vismap_pixel_polygons without the sub-pixel record
  UnmixInputs unmix;   // for unmix_pixels; `fine` empty when built with samples = 0
};

// The visibility-map mapping of the lens image: pixel (x, y) maps onto polygon P when the
// polygon at its center's undistorted position u is P and the disk of radius
// undistorted_radius(camera, lens, center, √2/2) around u — which holds the undistorted image
// of the pixel square — meets no silhouette edge, and the square's undistorted corners lie in
// the image (with
// exclude_all_boundaries: no edge between different polygons); point and segment tests on
// the map, exact. With samples s ≥ 1 also the unmixing's inputs: the pixels touching a
// silhouette whose square lies in the image, and the polygon at the undistorted position
// of each of their s × s samples (the cell centers of a regular grid in the lens pixel, as a
// sensor averages them); a pixel whose square leaves the image counts as on an edge (not a
// color source).
LensLabels vismap_lens_pixel_polygons(const visibility::VisibilityMap& map, const Camera& camera, const Lens& lens,
                                      bool exclude_all_boundaries, int samples);

// The item-buffer mapping of the lens image: the polygon that the sightline through each
// pixel center's undistorted position hits first (ray cast; kNone outside the pinhole image).
ImageU32 itembuffer_lens_pixel_polygons(const RayScene& rays, const visibility::ModelPolygons& model,
                                        const Camera& camera, const Lens& lens);

}  // namespace proxima::gibr
