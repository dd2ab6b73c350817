// `--scene NAME|FILE`: built-in name, then .json scene file, then any mesh file.
#include "proxima/scene/load.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "proxima/core/error.h"
#include "proxima/core/file_extension.h"
#include "proxima/core/limits.h"
#include "proxima/scene/builtin_scenes.h"
#include "proxima/scene/import.h"
#include "proxima/scene/scene_file.h"

namespace proxima {
namespace {

namespace fs = std::filesystem;

Scene load_unsanitized(const std::string& name_or_path) {
  // A built-in name wins over a file of the same name in the working directory.
  if (is_builtin_scene(name_or_path)) return make_builtin_scene(name_or_path);

  const fs::path path(name_or_path);
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    std::string names;
    for (const BuiltinSceneInfo& b : builtin_scenes())
      names += (names.empty() ? "" : ", ") + b.name;
    fail_missing_file("no such scene or file: " + name_or_path + " (built-in scenes: " + names + ")");
  }
  const std::string ext = lowercase_extension(path);
  return ext == ".json" ? load_scene_file(path) : import_mesh_file(path);
}

}  // namespace

Scene load_scene(const std::string& name_or_path) {
  try {
    Scene scene = load_unsanitized(name_or_path);
    // Files are checked before they allocate; this also holds built-in scenes to the limits.
    check_geometry_budget(name_or_path, scene.triangles.size(), scene.positions.size());
    sanitize_scene(scene, name_or_path);
    return scene;
  } catch (const std::filesystem::filesystem_error& e) {
    // Permissions, broken links and the like: still bad input, not an internal failure.
    fail_input(name_or_path + ": " + e.what());
  }
}

}  // namespace proxima
