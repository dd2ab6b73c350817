// Environment-map lookups for the reflection rays of a ReflectionFrame (reflection_frame.h):
// per reflective sample the mean over its rays of a plain, rectified (Wang et al. 2012) or
// box-projected (box_probe.h) lookup from the ray origin, so env mapping composes like the cluster and temporal methods
// (compose_reflections). Used by `reflect --method cluster --compare` and the viewer.
#pragma once

#include <vector>

#include "proxima/reflect/box_probe.h"
#include "proxima/reflect/reflection_frame.h"
#include "proxima/reflect/envmap_lookup.h"
#include "proxima/reflect/envmap_reflection.h"

namespace proxima {

// `method` is Plain, Rectified (with `rectify`) or BoxProbe (on the proxy `box`); others
// throw std::logic_error. Deterministic, parallel.
std::vector<vec3> envmap_frame_reflections(const Scene& scene, const ReflectionFrame& frame,
                                           const DistanceCubeMap& map, EnvmapMethod method,
                                           const RectifyOptions& rectify = {}, const Bounds3& box = {});

}  // namespace proxima
