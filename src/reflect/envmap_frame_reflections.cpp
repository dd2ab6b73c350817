#include "proxima/reflect/envmap_frame_reflections.h"

#include <stdexcept>

#include "proxima/core/parallel.h"

namespace proxima {

std::vector<vec3> envmap_frame_reflections(const Scene& scene, const ReflectionFrame& frame,
                                           const DistanceCubeMap& map, EnvmapMethod method,
                                           const RectifyOptions& rectify) {
  if (method != EnvmapMethod::Plain && method != EnvmapMethod::Rectified)
    throw std::logic_error("envmap_frame_reflections: plain or rectified only");
  std::vector<vec3> out(frame.sample_count(), vec3(0.0f));
  parallel_for(frame.sample_count(), 256, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      vec3 sum(0.0f);
      for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r)
        sum += method == EnvmapMethod::Plain
                   ? plain_lookup(map, scene.environment, frame.direction[r]).color
                   : rectified_lookup(map, scene.environment, frame.origin[i], frame.direction[r], rectify).color;
      out[i] = sum / float(frame.first_ray[i + 1] - frame.first_ray[i]);
    }
  });
  return out;
}

}  // namespace proxima
