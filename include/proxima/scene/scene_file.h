// JSON scene files (format and example in docs/formats.md): meshes (path + transform +
// material overrides), procedural objects, materials, cameras, camera paths, lights,
// environment, animation. Paths resolve relative to the scene file.
#pragma once

#include <filesystem>
#include <string>

#include "proxima/scene/scene.h"

namespace proxima {

// Throws InputError naming the file (and the JSON path of the bad value) on any problem.
Scene load_scene_file(const std::filesystem::path& path);

}  // namespace proxima
