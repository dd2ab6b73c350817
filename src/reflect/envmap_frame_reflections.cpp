#include "proxima/reflect/envmap_frame_reflections.h"

#include "proxima/core/parallel.h"

namespace proxima {

std::vector<vec3> envmap_frame_reflections(const Scene& scene, const ReflectionFrame& frame,
                                           const EnvmapInputs& inputs) {
  check_envmap_groups(inputs, frame.reflector);
  std::vector<vec3> out(frame.sample_count(), vec3(0.0f));
  parallel_for(frame.sample_count(), 256, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      vec3 sum(0.0f);
      for (uint32_t r = frame.first_ray[i]; r < frame.first_ray[i + 1]; ++r)
        sum += envmap_lookup(inputs, frame.reflector[i], scene.environment, frame.origin[i], frame.direction[r]).color;
      out[i] = sum / float(frame.first_ray[i + 1] - frame.first_ray[i]);
    }
  });
  return out;
}

}  // namespace proxima
