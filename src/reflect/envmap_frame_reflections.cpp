#include "proxima/reflect/envmap_frame_reflections.h"

#include <stdexcept>

#include "proxima/core/parallel.h"

namespace proxima {

std::vector<vec3> envmap_frame_reflections(const Scene& scene, const ReflectionFrame& frame,
                                           const DistanceCubeMap& map, EnvmapMethod method,
                                           const RectifyOptions& rectify, const Bounds3& box) {
  if (method != EnvmapMethod::Plain && method != EnvmapMethod::Rectified && method != EnvmapMethod::BoxProbe)
    throw std::logic_error("envmap_frame_reflections: plain, rectified or boxprobe only");
  auto lookup = [&](vec3 origin, vec3 dir) {
    if (method == EnvmapMethod::Plain) return plain_lookup(map, scene.environment, dir).color;
    if (method == EnvmapMethod::Rectified) return rectified_lookup(map, scene.environment, origin, dir, rectify).color;
    return box_probe_lookup(map, scene.environment, origin, dir, box).color;
  };
  std::vector<vec3> out(frame.sample_count(), vec3(0.0f));
  parallel_for(frame.sample_count(), 256, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      vec3 sum(0.0f);
      for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r)
        sum += lookup(frame.origin[i], frame.direction[r]);
      out[i] = sum / float(frame.first_ray[i + 1] - frame.first_ray[i]);
    }
  });
  return out;
}

}  // namespace proxima
