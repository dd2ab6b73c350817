// Algorithm 5 steps 1–2 (thesis ch. 3, §3.3): sample the scene with depth images from the
// area light and reconstruct occluder meshes from them.
#pragma once

#include <string>
#include <vector>

#include "proxima/depthimage/sampling.h"
#include "proxima/scene/light.h"
#include "proxima/shadows/light_setup.h"
#include "proxima/trace/ray_scene.h"

namespace proxima {

enum class ShadowSampling {
  Nrr,           // NRR images from the light's four corners (Algorithm 1)
  Conventional,  // conventional depth images from the four corners
  Peeling,       // four depth-peeling layers from the light's centre
  Geometry,      // no sampling: the original scene is the occluder (the ground truth)
};
const char* shadow_sampling_name(ShadowSampling s);  // "nrr" | "conventional" | "peeling" | "geometry"
// Throws InputError naming `flag` for anything else.
ShadowSampling parse_shadow_sampling(const std::string& name, const char* flag);

enum class ReconstructionMethod { Hybrid, Conventional };
const char* reconstruction_name(ReconstructionMethod m);  // "hybrid" | "conventional"
ReconstructionMethod parse_reconstruction(const std::string& name, const char* flag);

struct OccluderOptions {
  int resolution = 1024;  // of the reference images (square)
  Redundancy redundancy = Redundancy::Pixel;  // NRR's redundancy test
  ReconstructionMethod reconstruction = ReconstructionMethod::Hybrid;
  // Hybrid: planar runs of quads merged (reconstruct_hybrid): the same surface in fewer
  // triangles, so every shadow map of the occluders costs less.
  bool merge_planar_runs = true;
};

struct Occluders {
  Scene scene;                // one object per reconstructed image (Geometry: a copy of the input)
  size_t samples = 0;         // samples of the reference images I
  double reference_ms = 0.0;  // step 1: images I and (hybrid) the offset images H
  double reconstruct_ms = 0.0;  // step 2
};

// The reference cameras of step 1 (`resolution`² pixels): one per light corner, or for
// Peeling the one at the light's centre; none for Geometry.
std::vector<Camera> occluder_cameras(const AreaLight& light, const LightCameras& cams, ShadowSampling sampling,
                                     int resolution);

// Steps 1–2 for `sampling`. `rays` (the BVH of `scene`) is needed for NRR with visibility
// redundancy only. The hybrid reconstruction renders each image's offset image H with the
// same sampling rule (NRR over the four offset cameras, peeling of the offset camera).
Occluders build_occluders(const Scene& scene, const RayScene* rays, const AreaLight& light, const LightCameras& cams,
                          ShadowSampling sampling, const OccluderOptions& options);

}  // namespace proxima
