// Environment-map lookups for the reflection rays of a ReflectionFrame (reflection_frame.h):
// per reflective sample the mean over its rays of the inputs' method's lookup from the ray
// origin (plain, rectified, average, layered or box-projected; per group of reflectors when
// the inputs read an EnvmapSet), so env mapping composes like the cluster and temporal
// methods (compose_reflections). Used by `reflect --method cluster --compare` and the viewer.
#pragma once

#include <vector>

#include "proxima/reflect/envmap_reflection.h"
#include "proxima/reflect/reflection_frame.h"

namespace proxima {

// Each sample reads the maps of its reflector (envmap_lookup). Deterministic, parallel.
// Throws std::invalid_argument when the inputs have groups and a sample's reflector is in none.
std::vector<vec3> envmap_frame_reflections(const Scene& scene, const ReflectionFrame& frame,
                                           const EnvmapInputs& inputs);

}  // namespace proxima
