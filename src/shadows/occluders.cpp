// Algorithm 5 steps 1–2 (occluders.h). Paper: Xie Naiwen, PhD thesis, ch. 3 §3.3
// (../shared/papers/004_d1af2812aec5f9c7.txt, lines 888–925):
//   NRDI_i   images[i]: NRR (or conventional) image from light corner i, or peeling layer i
//            from the light's centre
//   M_i      the reconstructed mesh of images[i] (hybrid: Algorithm 4 with offsets[i] = H)
#include "proxima/shadows/occluders.h"

#include <utility>

#include "proxima/core/error.h"
#include "proxima/core/timer.h"
#include "proxima/reconstruct/reconstruction.h"

namespace proxima {

const char* shadow_sampling_name(ShadowSampling s) {
  switch (s) {
    case ShadowSampling::Nrr: return "nrr";
    case ShadowSampling::Conventional: return "conventional";
    case ShadowSampling::Peeling: return "peeling";
    case ShadowSampling::Geometry: return "geometry";
  }
  return "?";
}

ShadowSampling parse_shadow_sampling(const std::string& name, const char* flag) {
  for (ShadowSampling s : {ShadowSampling::Nrr, ShadowSampling::Conventional, ShadowSampling::Peeling,
                           ShadowSampling::Geometry})
    if (name == shadow_sampling_name(s)) return s;
  fail_input(std::string(flag) + ": unknown sampling '" + name + "' (nrr, conventional, peeling, geometry)");
}

const char* reconstruction_name(ReconstructionMethod m) {
  return m == ReconstructionMethod::Hybrid ? "hybrid" : "conventional";
}

ReconstructionMethod parse_reconstruction(const std::string& name, const char* flag) {
  if (name == "hybrid") return ReconstructionMethod::Hybrid;
  if (name == "conventional") return ReconstructionMethod::Conventional;
  fail_input(std::string(flag) + ": unknown reconstruction '" + name + "' (hybrid, conventional)");
}

namespace {

// Step 1 for one set of cameras (the reference cameras or their offset cameras).
std::vector<DepthImage> sample(const Scene& scene, const RayScene* rays, ShadowSampling sampling,
                               const std::vector<Camera>& cameras, Redundancy redundancy) {
  switch (sampling) {
    case ShadowSampling::Nrr: return sample_nrr(scene, cameras, redundancy, rays, true);
    case ShadowSampling::Conventional: return sample_conventional(scene, cameras, true);
    case ShadowSampling::Peeling: return sample_peeling(scene, cameras[0], 4, true);
    case ShadowSampling::Geometry: break;
  }
  return {};
}

}  // namespace

std::vector<Camera> occluder_cameras(const AreaLight& light, const LightCameras& cams, ShadowSampling sampling,
                                     int resolution) {
  std::vector<Camera> cameras;
  if (sampling == ShadowSampling::Peeling) cameras.push_back(light_camera(cams, light.point(0.5f, 0.5f), resolution));
  else if (sampling != ShadowSampling::Geometry)
    for (const vec3& c : light_corners(light)) cameras.push_back(light_camera(cams, c, resolution));
  return cameras;
}

Occluders build_occluders(const Scene& scene, const RayScene* rays, const AreaLight& light, const LightCameras& cams,
                          ShadowSampling sampling, const OccluderOptions& options) {
  Occluders out;
  if (sampling == ShadowSampling::Geometry) {
    out.scene = scene;
    return out;
  }
  const std::vector<Camera> cameras = occluder_cameras(light, cams, sampling, options.resolution);
  std::vector<Camera> offsets;
  for (const Camera& c : cameras) offsets.push_back(half_pixel_offset_camera(c));
  const bool hybrid = options.reconstruction == ReconstructionMethod::Hybrid;

  Stopwatch reference;
  const std::vector<DepthImage> images = sample(scene, rays, sampling, cameras, options.redundancy);
  const std::vector<DepthImage> offset_images =
      hybrid ? sample(scene, rays, sampling, offsets, options.redundancy) : std::vector<DepthImage>{};
  out.reference_ms = reference.elapsed_ms();

  Stopwatch reconstruct;
  std::vector<Mesh> meshes;
  for (size_t i = 0; i < images.size(); ++i) {
    out.samples += sample_count(images[i]);
    meshes.push_back(hybrid ? reconstruct_hybrid(images[i], offset_images[i], nullptr, options.merge_planar_runs)
                            : reconstruct_conventional(images[i]));
  }
  out.scene = reconstruction_scene(meshes, std::string(shadow_sampling_name(sampling)) + "-reconstruction");
  out.reconstruct_ms = reconstruct.elapsed_ms();
  return out;
}

}  // namespace proxima
