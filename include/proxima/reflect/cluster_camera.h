// The pinhole camera of one cluster of reflective pixels (thesis ch. 4 §4.4, Figs. 24–25):
// fitting plane (P_c, n_c) as near plane, eye mirrored to e0, centre moved towards P_c so
// the projected start and end points of the cluster's reflection rays have similar extents,
// image window = their bounding box on the plane, resolution from the pixel footprint.
#pragma once

#include <optional>
#include <span>

#include "proxima/core/camera.h"

namespace proxima {

struct ClusterCameraInput {
  std::span<const vec3> points;   // P_i: surface points of the cluster's pixels (world)
  std::span<const vec3> normals;  // n_i: unit normals facing the eye, same size
  std::span<const vec3> ray_ends; // Q: far end points of every reflection ray of the cluster
                                  //    (start + far_distance · unit direction)
  vec3 eye{0.0f};                 // e
  float pixel_footprint = 0.0f;   // p: mean distance between neighbouring pixels' points (> 0)
  float resolution_scale = 1.0f;  // texels per footprint along each axis (Table 17)
  int max_image_side = 2048;      // cap on width and height
  float plane_tolerance = 0.0f;   // coplanarity tolerance in meters (≥ 0)
};

struct ClusterCamera {
  Camera camera;             // pinhole at e_c looking through the image window (square pixels)
  vec3 plane_point{0.0f};    // P_c = mean P_i
  vec3 plane_normal{0.0f};   // n_c = normalized mean n_i (faces the eye's side)
  float clip_offset = 0.0f;  // near plane: only points x with dot(x − P_c, n_c) > clip_offset
                             // belong to the depth image: half the plane tolerance for a
                             // planar cluster (the fitting plane, clear of the reflector's own
                             // surface); for a curved one the lowest P_i minus the tolerance
  vec3 mirrored_eye{0.0f};   // e0
  float f = 1.0f;            // d_n / d_f (Eq. 6), in (0, 1]; 1 for a planar cluster
  float d_n = 0.0f;          // diagonal of the start points' box on the plane, seen from e0
  float d_f = 0.0f;          // diagonal of the end points' box on the plane, seen from e0
  bool planar = false;       // every P_i within plane_tolerance of the plane, n_i = n_c
};

// Builds the cluster camera. Texels ≈ scale² · min(window area / p², 4 · pixels): one
// texel per footprint, but no more than a few per pixel of the cluster (a curved or glossy
// cluster's window is much larger than its pixels' footprints and holds a minified scene). e_c = e0 + (P_c − e0)·(1 − f): e0 itself for a planar cluster
// (every reflection ray then passes through e0), nearer the plane for a convex one. f is
// raised (towards e0) when the window would need a half field of view above 75°.
// nullopt when the cluster is empty or the eye lies on its fitting plane.
std::optional<ClusterCamera> build_cluster_camera(const ClusterCameraInput& input);

}  // namespace proxima
