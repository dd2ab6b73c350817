// One entry point for `--scene NAME|FILE`: a built-in scene name, a .json scene file, or
// any mesh file assimp reads. The result is sanitized (scene.h).
#pragma once

#include <string>

#include "proxima/scene/scene.h"

namespace proxima {

// Throws InputError naming the scene / file and the problem.
Scene load_scene(const std::string& name_or_path);

}  // namespace proxima
