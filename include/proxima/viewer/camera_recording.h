// `proxima view --record FILE`: the flown camera as a camera path (scene/camera_path.h),
// written as a JSON scene file `{"builtin": SCENE, "camera_paths": [...]}` (docs/formats.md)
// so every command reads it back: `proxima render --scene FILE --path recorded --frame F`.
#pragma once

#include <filesystem>
#include <string>

#include "proxima/scene/camera_path.h"
#include "proxima/viewer/fly_camera.h"

namespace proxima {

inline constexpr const char* kRecordedPathName = "recorded";

struct CameraRecorder {
  CameraPath path{kRecordedPathName, {}, 1, {0.0f, 1.0f, 0.0f}};
  float time = 0.0f;  // seconds since the recording started
};

// Advances the clock by dt_s and adds a key for `fly` when it is the first one or the
// view changed (keys keep strictly increasing times).
void record_camera(CameraRecorder& recorder, const FlyCamera& fly, float dt_s, bool changed);

// Writes the scene file atomically; `frames` = one per key (at least 1). Throws InputError
// naming the file.
void write_recorded_path(const std::filesystem::path& file, const std::string& builtin_scene,
                         const CameraRecorder& recorder);

}  // namespace proxima
