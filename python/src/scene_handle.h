// A Scene as Python holds it (proxima.Scene): the scene, its Embree BVH built on first use
// and kept (many views render without rebuilding it), and a lock that keeps material edits
// out of running renders. Geometry is read-only from Python, so the BVH stays valid.
#pragma once

#include <memory>
#include <mutex>
#include <shared_mutex>

#include "proxima/scene/scene.h"
#include "proxima/trace/ray_scene.h"

namespace proxima::python {

class SceneHandle {
 public:
  explicit SceneHandle(Scene scene) : scene_(std::move(scene)) {}

  // For readers that hold no lock: names, counts, geometry (never changed after loading).
  const Scene& scene() const { return scene_; }

  // Readers of materials (renders, techniques) hold this for the whole call; call without
  // the GIL (a writer may be waiting for it with the GIL released).
  std::shared_lock<std::shared_mutex> read_lock() const { return std::shared_lock(mutex_); }
  // Material edits hold this: the scene to change. Call without the GIL.
  std::unique_lock<std::shared_mutex> write_lock() { return std::unique_lock(mutex_); }
  Scene& mutable_scene() { return scene_; }

  // The BVH of the scene's rest pose, built on the first call (thread-safe); call without
  // the GIL.
  const RayScene& rays() const;

 private:
  Scene scene_;
  mutable std::shared_mutex mutex_;
  mutable std::once_flag rays_once_;
  mutable std::unique_ptr<RayScene> rays_;
};

}  // namespace proxima::python
