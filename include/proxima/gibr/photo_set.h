// Calibrated photographs for hybrid geometry- and image-based rendering (Funkhouser,
// section 2: "a set of photographic images calibrated with 3D camera viewpoints"): the
// synthetic ones are reference renders (trace/) of a textured, lit copy of a polygonal model
// from seeded poses around its walkthrough path; real ones come with a camera file
// (docs/gibr.md: JSON, intrinsics + pose per image).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "proxima/core/camera.h"
#include "proxima/core/image.h"
#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"
#include "proxima/trace/reference_renderer.h"

namespace proxima::gibr {

struct PhotoSceneOptions {
  double period = 1.0;    // meters per texture repeat (planar world-space uvs)
  int texture_size = 64;  // texture pixels per repeat (period / size = finest detail)
  uint64_t seed = 1;
};

// A copy of `model` whose every material gets a procedural high-frequency texture (checker
// of 8 × 8 cells per repeat times per-pixel value noise, tinted per channel, times the
// material's diffuse color) and whose uvs are world coordinates / period projected along the
// dominant axis of each vertex normal, so texture detail is fixed in world space and any
// misalignment of a mapped photograph shows. Geometry, lights and paths are unchanged.
Scene make_photo_scene(const Scene& model, const PhotoSceneOptions& options = {});

struct PhotoPoseOptions {
  int count = 100;
  int width = 320, height = 240;
  double jitter = 0.2;       // meters: position offset (uniform in a cube of this half-size)
  double yaw_deg = 30.0;     // view direction turned by uniform ±yaw about +Y
  double pitch_deg = 10.0;   // and tilted by uniform ±pitch
  double backoff = 0.0;      // meters moved back against the view direction (shortened where blocked)
  uint64_t seed = 1;
};

// `count` cameras at seeded uniform times along `path`, each jittered around the path's
// camera; a jittered position whose segment from the path point is blocked (it would stand
// inside or behind a wall) falls back to the path point. Deterministic for a seed.
std::vector<Camera> photo_poses(const RayScene& rays, const CameraPath& path, const PhotoPoseOptions& options,
                                float near, float far);

// `count` novel-view cameras off the walk path (none of them on the photographs' path): at
// evenly spaced times along `path` (the first and last key for count ≥ 2), the path's camera
// translated by `offset` meters along its right vector, alternately +/− per view, plus
// offset / 2 along its up vector, alternately +/+/−/− — orientation unchanged. An offset
// whose segment from the path point is blocked is halved (up to 4 times, else 0 — the
// view stays on the path). Deterministic; no random numbers.
std::vector<Camera> offpath_poses(const RayScene& rays, const CameraPath& path, int count, int width, int height,
                                  double offset, float near, float far);

// The photograph: render_reference with k×k supersampling (pixels straddling silhouettes
// mix the surfaces they cover, as a real photograph's do), n² area-light samples, no
// reflections. Linear RGB, 3 channels.
ImageF render_photo(const Scene& scene, const RayScene& rays, const Camera& camera, int supersample, uint64_t seed);
// Its renderer settings (e.g. to render a ground truth a band of rows at a time).
ReferenceOptions photo_render_options(int supersample, uint64_t seed);

struct CalibratedPhoto {
  std::string image;  // file name, relative to the camera file's directory
  Camera camera;
  // Lens and exposure (docs/gibr.md): radial distortion of the normalized image coordinates,
  // x_d = x (1 + k1 r² + k2 r⁴); exposure = the image's linear value / the scene's radiance.
  double k1 = 0.0, k2 = 0.0, exposure = 1.0;
};

// The pinhole photograph of `camera` from a photograph taken through a lens with radial
// distortion (k1, k2): each pixel center's normalized coordinates distorted and the image
// sampled there (bilinear, linear RGB). `valid` (optional) gets 1 per pixel whose distorted
// position lies inside the image, 0 (and black) elsewhere.
ImageF undistort_photo(const ImageF& image, const Camera& camera, double k1, double k2, ImageU8* valid = nullptr);
// The inverse: what a lens with (k1, k2) makes of the pinhole photograph `image` (each pixel's
// undistorted position by fixed-point iteration, then bilinear; outside → black). For tests
// and for making distorted photographs of synthetic scenes.
ImageF distort_photo(const ImageF& image, const Camera& camera, double k1, double k2);

// Camera file (docs/gibr.md):
// {"format": "proxima-cameras", "version": 1, "photos": [{"image": "photo_000.png",
//  "width": 320, "height": 240, "vfov_deg": 60, "position": [x, y, z],
//  "orientation": [w, x, y, z], "near": 0.01, "far": 1000, "k1": 0, "k2": 0, "exposure": 1}]}
// orientation = camera → world rotation (camera looks down −Z, +Y up), as core/camera.h;
// k1, k2, exposure optional (defaults 0, 0, 1; written only when they differ). k1, k2 must
// be finite, |k| ≤ 1, and keep the distortion monotonic over the image (InputError otherwise);
// exposure finite and > 0.
void write_camera_file(const std::filesystem::path& path, const std::vector<CalibratedPhoto>& photos);
// InputError naming the file for a missing or malformed file or an invalid camera.
std::vector<CalibratedPhoto> read_camera_file(const std::filesystem::path& path);

}  // namespace proxima::gibr
