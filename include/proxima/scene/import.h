// Import of mesh files through assimp (OBJ, glTF 2.0 / GLB, PLY and whatever else assimp
// reads). Material mapping (glTF metallic/roughness, OBJ Ks/Ns → s, g) is in docs/formats.md.
#pragma once

#include <filesystem>

#include "proxima/scene/scene.h"

namespace proxima {

// One object per assimp mesh (named after the mesh, else its node), node transforms
// applied, smooth normals generated where missing. Diffuse textures load relative to the
// file; missing or embedded ones are skipped with a warning on stderr. Not sanitized
// (load_scene does that). Throws InputError naming the file for a missing, unreadable or
// malformed file, or one with no triangles.
Scene import_mesh_file(const std::filesystem::path& path);

// Writes a scene's geometry (rest pose) as Wavefront OBJ + MTL beside it (for round trips
// and for handing scenes to other tools), textures as <stem>_texture<i>.png. Each file is
// written atomically; import_mesh_file of the result gives back the triangles in order and
// the materials' s, g, diffuse and emission.
void write_obj(const std::filesystem::path& path, const Scene& scene);

}  // namespace proxima
