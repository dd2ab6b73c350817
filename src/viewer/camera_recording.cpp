#include "proxima/viewer/camera_recording.h"

#include <nlohmann/json.hpp>

#include "proxima/core/atomic_file.h"

namespace proxima {

void record_camera(CameraRecorder& r, const FlyCamera& fly, float dt_s, bool changed) {
  if (!r.path.keys.empty()) r.time += std::max(dt_s, 1e-3f);
  if (!r.path.keys.empty() && !changed) return;
  r.path.keys.push_back({r.time, fly.position, fly.position + fly_forward(fly), fly.vfov_deg});
  r.path.frames = int(r.path.keys.size());
}

void write_recorded_path(const std::filesystem::path& file, const std::string& builtin_scene,
                         const CameraRecorder& r) {
  auto v3 = [](vec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  nlohmann::json keys = nlohmann::json::array();
  for (const CameraKey& k : r.path.keys)
    keys.push_back({{"time", k.time}, {"position", v3(k.position)}, {"target", v3(k.target)}, {"vfov_deg", k.vfov_deg}});
  nlohmann::json path = {{"name", r.path.name}, {"frames", std::max(1, r.path.frames)}, {"up", v3(r.path.up)},
                         {"keys", keys}};
  nlohmann::json doc = {{"builtin", builtin_scene}, {"camera_paths", nlohmann::json::array({path})}};
  write_text_file(file, doc.dump(2) + "\n");
}

}  // namespace proxima
