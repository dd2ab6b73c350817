#include "scene_handle.h"

namespace proxima::python {

const RayScene& SceneHandle::rays() const {
  // A failed build (Embree out of memory) throws out of call_once and is retried next time.
  std::call_once(rays_once_, [this] { rays_ = std::make_unique<RayScene>(scene_); });
  return *rays_;
}

}  // namespace proxima::python
