// Built-in procedural scenes, deterministic, listed by `proxima scenes`.
#pragma once

#include <string>
#include <vector>

#include "proxima/scene/scene.h"

namespace proxima {

struct BuiltinSceneInfo {
  std::string name;
  std::string description;
};

// cornell, room-reflector, living-room, bathroom.
std::vector<BuiltinSceneInfo> builtin_scenes();

bool is_builtin_scene(const std::string& name);

// Builds a built-in scene; throws InputError for an unknown name (listing the known ones).
Scene make_builtin_scene(const std::string& name);

}  // namespace proxima
